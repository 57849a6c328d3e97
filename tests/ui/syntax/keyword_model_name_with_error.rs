// The model is named after a keyword (`mod_` is its module): an error
// elsewhere must not add one about the placeholder module.
autosim::model! {
    model Mod;
    body B { rotat: 1 }
}

fn main() {}
