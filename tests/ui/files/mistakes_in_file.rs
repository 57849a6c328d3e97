// Every mistake of a model file is its own error, each with its place in
// the file and an excerpt.
autosim::model!(file = "tests/ui/files/two_mistakes.sim");

fn main() {}
