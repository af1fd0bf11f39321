//! Kinematic chain elements as NC data text, for the tests of chain-defined transformations.

/// Chain elements: (name, type, next, parallel, off_dir, axis, a_off).
pub type El<'a> = (&'a str, &'a str, &'a str, &'a str, [f64; 3], &'a str, f64);

/// The `$NK_` assignments of `els`, element i at index i.
pub fn elements(els: &[El]) -> String {
    let mut out = String::new();
    for (i, (name, ty, next, par, dir, axis, a_off)) in els.iter().enumerate() {
        out += &format!("$NK_NAME[{i}]=\"{name}\"\n$NK_TYPE[{i}]=\"{ty}\"\n");
        if !next.is_empty() {
            out += &format!("$NK_NEXT[{i}]=\"{next}\"\n");
        }
        if !par.is_empty() {
            out += &format!("$NK_PARALLEL[{i}]=\"{par}\"\n");
        }
        out += &(0..3).map(|k| format!("$NK_OFF_DIR[{i},{k}]={:?}\n", dir[k])).collect::<String>();
        if !axis.is_empty() {
            out += &format!("$NK_AXIS[{i}]=\"{axis}\"\n");
        }
        if *a_off != 0.0 {
            out += &format!("$NK_A_OFF[{i}]={a_off:?}\n");
        }
    }
    out
}
