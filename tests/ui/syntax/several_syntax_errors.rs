// Syntax errors are all reported too (the parser recovers at the next entry
// or item); the model is not resolved until they are fixed.
autosim::model! {
    model Arm;
    body Upper { rotat: 1, mass 2 }
    body Lower { parent: Upper rotate: 1 }
    output angle = ;
}

fn main() {}
