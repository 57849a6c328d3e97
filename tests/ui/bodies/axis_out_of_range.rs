// An axis number that does not exist, and axes written as letters (each
// names the number it means).
autosim::model! {
    model Gimbal;
    body Frame { rotate: [1, 4, 3] }
    body Rotor { rotate: y, translate: [X] }
}

fn main() {}
