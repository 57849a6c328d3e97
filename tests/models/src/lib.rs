//! Every example model, compiled twice: through `autosim::model!` and
//! through `build.rs` (`autosim::build`). Compiled under `#![deny(warnings)]`
//! (and clippy in CI), so generated code must be warning-free.
#![deny(warnings)]
#![deny(missing_docs)]

/// The models expanded by the macro.
pub mod via_macro {
    autosim::model!(file = "../../examples/models/andrews.sim");
    autosim::model!(file = "../../examples/models/bicycle.sim");
    autosim::model!(file = "../../examples/models/bouncing_ball.sim");
    autosim::model!(file = "../../examples/models/chain_planar_1.sim");
    autosim::model!(file = "../../examples/models/chain_planar_10.sim");
    autosim::model!(file = "../../examples/models/chain_planar_2.sim");
    autosim::model!(file = "../../examples/models/chain_planar_2_f32.sim");
    autosim::model!(file = "../../examples/models/chain_planar_3.sim");
    autosim::model!(file = "../../examples/models/chain_planar_5.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_1.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_10.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_2.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_20.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_3.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_3_stiff.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_5.sim");
    autosim::model!(file = "../../examples/models/chain_spatial_7.sim");
    autosim::model!(file = "../../examples/models/features.sim");
    autosim::model!(file = "../../examples/models/four_bar.sim");
    autosim::model!(file = "../../examples/models/pendulum_end_stop.sim");
    autosim::model!(file = "../../examples/models/quarter_car_bump_stop.sim");
    autosim::model!(file = "../../examples/models/rolling_disc.sim");
    autosim::model!(file = "../../examples/models/satellite.sim");
    autosim::model!(file = "../../examples/models/satellite_events.sim");
    autosim::model!(file = "../../examples/models/satellite_small.sim");
}

/// Scenes: one model file tailored at the use site.
pub mod scenes {
    use autosim_test_support::models_from;
    models_from! { "../../examples/models/satellite.sim":
        SatelliteSmallScene, small = [B, E, F];
        RigidBoom, lock = [q9, q10], outputs = [roll, pitch, yaw];
    }
    models_from! { "../../examples/models/chain_spatial_5.sim": ChainSpatial5F32, float = f32; }
    models_from! { "../../examples/models/four_bar.sim": FourBarF32, float = f32; }
}

/// Models with `derivatives_lanes` (the `lanes = true` option): every kind
/// of generated code, for `tests/lanes.rs`.
pub mod lanes {
    autosim::model!(
        file = "../../examples/models/chain_spatial_7.sim",
        lanes = true
    );
    autosim::model!(
        file = "../../examples/models/chain_spatial_10.sim",
        lanes = true
    );
    autosim::model!(
        file = "../../examples/models/chain_spatial_20.sim",
        lanes = true
    );
    autosim::model!(
        file = "../../examples/models/chain_planar_10.sim",
        lanes = true
    );
    autosim::model!(file = "../../examples/models/four_bar.sim", lanes = true);
    autosim::model!(
        file = "../../examples/models/rolling_disc.sim",
        lanes = true
    );
    autosim::model!(file = "../../examples/models/bicycle.sim", lanes = true);
    autosim::model!(file = "../../examples/models/satellite.sim", lanes = true);
    autosim::model!(
        file = "../../examples/models/quarter_car_bump_stop.sim",
        lanes = true
    );
    autosim::model!(
        file = "../../examples/models/chain_planar_2_f32.sim",
        lanes = true
    );
    autosim::model! {
        /// A pendulum driven by a torque that varies in time: each lane
        /// must read its own time.
        model DrivenPendulum;
        settings { lanes: true }
        parameters {
            m = 1.3 [kg],
            L = 0.7 [m],
            g = 9.81 [m/s^2],
            A = 2.0 [N m],
            w = 3.0 [rad/s],
            /// A torque rate.
            r = 0.5 [N m/s],
        }
        body Rod { rotate: 1, q: [q], u: [u], mass: m, cm: [0, 0, -L], inertia: 0 }
        moment drive { on: Rod, reaction: N, about: n1, magnitude: A*sin(w*t) + r*t }
        gravity = -g*n3;
    }
}

/// The models written by the build script.
pub mod via_build {
    autosim::include_model!(andrews);
    autosim::include_model!(bicycle);
    autosim::include_model!(bouncing_ball);
    autosim::include_model!(chain_planar1);
    autosim::include_model!(chain_planar10);
    autosim::include_model!(chain_planar2);
    autosim::include_model!(chain_planar2_f32);
    autosim::include_model!(chain_planar3);
    autosim::include_model!(chain_planar5);
    autosim::include_model!(chain_spatial1);
    autosim::include_model!(chain_spatial10);
    autosim::include_model!(chain_spatial2);
    autosim::include_model!(chain_spatial20);
    autosim::include_model!(chain_spatial3);
    autosim::include_model!(chain_spatial3_stiff);
    autosim::include_model!(chain_spatial5);
    autosim::include_model!(chain_spatial7);
    autosim::include_model!(features);
    autosim::include_model!(four_bar);
    autosim::include_model!(pendulum_end_stop);
    autosim::include_model!(quarter_car_bump_stop);
    autosim::include_model!(rolling_disc);
    autosim::include_model!(satellite);
    autosim::include_model!(satellite_events);
    autosim::include_model!(satellite_small);
}
