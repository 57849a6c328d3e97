autosim::model!(file = "tests/ui/files/missing.sim");

fn main() {}
