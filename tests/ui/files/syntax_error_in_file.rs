autosim::model!(file = "tests/ui/files/bad_syntax.sim");

fn main() {}
