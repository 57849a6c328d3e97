//! `discrete` and `event` items: what the parser reads, and its errors.

use super::errors::check;
use super::satellite::summary_of;

#[test]
fn discrete_and_event_items_are_read() {
    let text = "model Ball;
        discrete resting = 0, toff [s] = -1.5, mode [1];
        /// The ball hits the floor.
        event bounce [m] \"impact\" {
            indicator: h,
            direction: falling,
            reset: { v: -e*v, h: 0 },
            set: { resting: 1 },
        }
        event done { indicator: t - 10, stop: true }";
    assert_eq!(
        summary_of(text),
        "model Ball docs []\n\
         discrete resting = 0, toff [s] = -1.5, mode [1]\n\
         event bounce [m] \"impact\" { indicator: h, direction: falling } set { resting: 1 } reset { v: -e*v, h: 0 }\n\
         event done { indicator: t - 10, stop: true }\n"
    );
}

#[test]
fn event_block_errors() {
    check(
        "model M;\nevent e { indicator: h, directon: rising }",
        r#"
test.sim:2:25: error: unknown event option `directon`
  |
2 | event e { indicator: h, directon: rising }
  |                         ^^^^^^^^
  = help: did you mean `direction`?
  = note: the event options are: indicator, direction, set, reset, stop
"#,
    );
    check(
        "model M;\nevent e { indicator: h, reset: v = 0 }",
        r#"
test.sim:2:32: error: expected `{` with the assignments of `reset`, found `v`
  |
2 | event e { indicator: h, reset: v = 0 }
  |                                ^
  = help: write `reset: { v: -e*v }`: each entry a name and its new value
"#,
    );
    check(
        "model M;\nevent e { indicator: h, set: { m = 1 } }",
        r#"
test.sim:2:34: error: expected `:` after `m`, found `=`
  |
2 | event e { indicator: h, set: { m = 1 } }
  |                                  ^
  = help: assignments are written `m: <new value>`
"#,
    );
    check(
        "model M;\nevent e { indicator: comp < 0, direction: falling }",
        r#"
test.sim:2:27: error: expected `,` or `}` after the indicator, found `<`
  |
2 | event e { indicator: comp < 0, direction: falling }
  |                           ^
  = help: an indicator is a value whose sign changes at the event, not a comparison: for `a < b` write `indicator: a - b, direction: falling` (the event fires as `a - b` goes below zero)
"#,
    );
}
