//! The program of a model with events against its symbolic equations (a
//! differential test of the optimizer with the discrete modes switched):
//! the interpreter reads the discrete values it is given, so the
//! derivatives, the event indicators and each event's new values of
//! `satellite_events.sim` (whose thruster modes switch the torques) equal
//! the unoptimized expressions evaluated with the same modes, at random
//! states; and the bouncing ball's derivatives follow its resting mode
//! (the analytic free fall, or rest).

use autosim_core::diag::SourceFile;
use autosim_core::expr::{Bindings, NoUserFunctions};
use autosim_core::opt::{At, BlockKind, Interpreter, UserCalls};
use autosim_core::pipeline::{Compiled, compile_source};
use autosim_test_support::{Rng, api, rel_err, worst_of};

fn compile_file(name: &str) -> Compiled {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/models")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let file = SourceFile::new(name, text);
    compile_source(&file).unwrap_or_else(|d| panic!("{}", d.render(&file)))
}

/// The default parameter values of `c`.
fn defaults(c: &Compiled) -> Vec<f64> {
    let params = &c.program.interface.model.parameters;
    params.iter().map(|p| p.default).collect()
}

/// The bindings of the symbolic equations at `t`, `x`, the discrete values
/// `d` and the subroutine outputs `cmd` (by name).
fn bindings(c: &Compiled, t: f64, x: &[f64], d: &[f64], cmd: &[(&str, f64)]) -> Bindings {
    let sys = &c.model.system;
    let eqs = &c.equations;
    let mut b = Bindings::with_defaults(&sys.arena);
    let states = eqs.coordinates.iter().chain(&eqs.speeds).chain(&eqs.states);
    for (s, v) in states.zip(x) {
        b.set(*s, *v);
    }
    for (s, v) in sys.discrete().iter().zip(d) {
        b.set(*s, *v);
    }
    for (name, v) in cmd {
        b.set(
            sys.arena.symbol_named(name).expect("a subroutine output"),
            *v,
        );
    }
    b.set(sys.time(), t);
    b
}

#[test]
fn satellite_events_program_matches_its_equations_in_every_mode() {
    let c = compile_file("satellite_events.sim");
    let prog = &c.program;
    let sys = &c.model.system;
    let it = Interpreter::new(prog, &defaults(&c));
    let n_states = prog.states().len();
    let n_discrete = prog.interface.model.discrete.len();
    assert_eq!(n_discrete, 6);
    let mut rng = Rng::new(0x5eed_e7e7);
    let (mut worst, mut modes_differ) = (0.0_f64, 0);
    for _ in 0..40 {
        let t = rng.uniform(0.0, 15.0);
        let x: Vec<f64> = (0..n_states).map(|_| rng.uniform(-1.0, 1.0)).collect();
        // fire1..3 in {-1, 0, 1}, toff1..3 any time.
        let d: Vec<f64> = (0..n_discrete)
            .map(|k| match k < 3 {
                true => (rng.uniform(0.0, 3.0).floor() - 1.0).clamp(-1.0, 1.0),
                false => rng.uniform(0.0, 15.0),
            })
            .collect();
        let cmd = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
        let mut function = |_: usize, _: &[f64]| f64::NAN;
        let mut subroutine = |_: usize, _: &[f64]| cmd.to_vec();
        let mut user = UserCalls {
            function: &mut function,
            subroutine: &mut subroutine,
        };
        let at = At {
            t,
            x: &x,
            inputs: &[],
            discrete: &d,
        };
        let b = bindings(&c, t, &x, &d, &[("clkcmd", cmd[0]), ("camcmd", cmd[1])]);

        let dx = it.derivatives(at, &mut user).expect("regular");
        let (mut want, du) = api::derivatives(sys, &c.equations, &b);
        want.extend(du);
        let e = rel_err(&dx, &want);
        assert!(e < 1e-10, "derivatives: {e:e} with modes {d:?}");
        worst = worst_of(worst, e);
        // The initial modes would give other accelerations.
        let initial = At {
            discrete: &[],
            ..at
        };
        let dx0 = it.derivatives(initial, &mut user).expect("regular");
        if d[..3] != [0.0; 3] && rel_err(&dx0, &want) > 1e-6 {
            modes_differ += 1;
        }

        let g = it
            .block_at(BlockKind::EventIndicators, at, &mut user)
            .expect("indicators");
        let events = sys.events();
        let roots: Vec<_> = events.iter().map(|e| e.indicator).collect();
        let want_g = sys.arena.eval_many(&roots, &b, &mut NoUserFunctions);
        let e = rel_err(&g, &want_g);
        assert!(e < 1e-12, "indicators: {e:e}");
        worst = worst_of(worst, e);

        for (k, event) in events.iter().enumerate() {
            let values = it
                .block_at(BlockKind::EventAction(k), at, &mut user)
                .expect("actions");
            let roots: Vec<_> = event
                .sets
                .iter()
                .chain(&event.resets)
                .map(|a| a.1)
                .collect();
            let want = sys.arena.eval_many(&roots, &b, &mut NoUserFunctions);
            assert_eq!(values.len(), want.len(), "event {}", event.name);
            let e = rel_err(&values, &want);
            assert!(e < 1e-12, "event {}: {e:e}", event.name);
            worst = worst_of(worst, e);
        }
    }
    eprintln!("satellite_events program against its equations: worst {worst:.1e}");
    assert!(
        modes_differ > 10,
        "the modes changed the derivatives only {modes_differ} times"
    );
}

#[test]
fn the_bouncing_balls_derivatives_follow_its_resting_mode() {
    let c = compile_file("bouncing_ball.sim");
    let it = Interpreter::new(&c.program, &defaults(&c));
    let mut function = |_: usize, _: &[f64]| f64::NAN;
    let mut subroutine = |_: usize, _: &[f64]| Vec::new();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    let x = [0.7, -1.3];
    for (resting, dv) in [(0.0, -9.81), (1.0, 0.0)] {
        let at = At {
            t: 0.0,
            x: &x,
            inputs: &[],
            discrete: &[resting],
        };
        let dx = it.derivatives(at, &mut user).expect("derivatives");
        assert_eq!(dx, vec![-1.3, dv], "resting = {resting}");
    }
}
