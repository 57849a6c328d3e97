// An axis number that does not exist, axes written as letters (each names
// the number it means) and a misspelt `quaternion`.
autosim::model! {
    model Gimbal;
    body Frame { rotate: [1, 4, 3] }
    body Rotor { rotate: y, translate: [X] }
    body Gyro { rotate: quaternoin }
}

fn main() {}
