// A misspelled formulation among the macro's options: the error points at
// it and names the likely intended one.
autosim::model!(file = "tests/ui/files/swing.sim", formulation = recursve);

fn main() {}
