autosim::model! {}

fn main() {}
