autosim::model!(file = 3);

fn main() {}
