// `//` starts a comment even inside a unit's brackets: in a model file the
// `]` is then never seen. (Inline, rustc reports the unclosed `[` itself.)
autosim::model!(file = "tests/ui/files/unit_comment.sim");

fn main() {}
