// Four independent mistakes: each is reported, none hides another, and a
// body that failed (`Upper`, `Lower`) causes no follow-on errors where it
// is used.
autosim::model! {
    model Arm;
    parameters { k = 100 [N m/rad] }
    body Upper { rotate: [1, 4, 3] }
    body Lower { parent: Uper, rotate: 1 }
    moment spring { on: Lower, reaction: Upper, about: n1, magnitude: -kk*q(Lower) }
    output tip = n1;
}

fn main() {}
