// A scene option naming what the model lacks is shown at the name in the
// macro's options, not at the file's path.
autosim::model!(file = "tests/ui/files/swing.sim", outputs = [Lx]);

fn main() {}
