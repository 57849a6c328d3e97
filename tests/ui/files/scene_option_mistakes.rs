// Every mistake among the macro's options is reported at once, each with
// the wording the model's `settings` use: an unknown option (with the list
// of options), a float type, a threshold out of range, a key given twice.
autosim::model!(
    file = "tests/ui/files/swing.sim",
    float = f16,
    threshold = 30,
    colour = red,
    lock = [q1],
    lock = [q1],
    linearize = yes
);

fn main() {}
