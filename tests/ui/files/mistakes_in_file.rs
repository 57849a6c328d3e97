// Every mistake of a model file is its own error, each with its place in
// the file and an excerpt; the program's use of the model adds none.
autosim::model!(file = "tests/ui/files/two_mistakes.sim");

fn main() {
    let mut model = pendulum::Pendulum::new();
    model.set_parameters(pendulum::Parameters { m: 2.0, ..Default::default() });
    let x = [0.1; pendulum::N_STATES];
    println!("{:?}", model.derivatives(0.0, &x));
}
