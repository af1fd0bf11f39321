//! What the tests of chain-defined transformations share: the six-axis test machine, chain
//! elements as NC data text, and axis vectors compared with a tolerance.

/// Machine with channel axes X, Y, Z, A, B, C (machine axes X1..C1), C a modulo rotary axis, no
/// transformation.
pub const SIX: &str =
    "$MA_IS_ROT_AX[A1]=TRUE\n$MA_IS_ROT_AX[B1]=TRUE\n$MA_IS_ROT_AX[C1]=TRUE\n$MA_ROT_IS_MODULO[C1]=TRUE\n";

/// A channel axis vector.
pub type Axes = [f64; 20];

/// `values` in the first channel axes, 0 in the others.
pub fn axes(values: &[f64]) -> Axes {
    let mut v = [0.0; 20];
    v[..values.len()].copy_from_slice(values);
    v
}

/// Same length and every component within `tol`.
pub fn near(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

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
