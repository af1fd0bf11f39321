//! The stock in a checkpoint: a versioned binary, run-length coded (a cut part is mostly runs
//! of equal cells: the untouched top, a pocket's floor), as base64 text for the JSON of the
//! channel state. Little endian throughout.
//!
//! Format 1: `b'M'`, res, x0, y0 (f64), nx, ny (u32), top_max, volume (f64), the runs of first
//! intervals (u32 count, then per run u32 length, f32 bottom, f32 top), the further intervals
//! (u32 cells, per cell u32 index, u32 count, count × (f32, f32)), the runs of pens (u32
//! count, per run u32 length, u8 pen); or `b'T'`, res, z0 (f64),
//! n (u32), volume (f64), then the runs of outer and of inner radii (u32 count, per run u32
//! length, f64 radius).

use std::collections::BTreeMap;

use super::dexel::DexelGrid;
use super::profile::Profile;
use super::{MAX_CELLS, Stock};

/// The format [`encode`] writes.
pub const FORMAT: u32 = 1;

/// The stock as base64 text of format [`FORMAT`].
pub fn encode(stock: &Stock) -> String {
    let mut w = Vec::new();
    match stock {
        Stock::Milling(g) => {
            let (spans, extra, top_max, marks) = g.raw();
            let (nx, ny) = g.size();
            let (x0, y0) = g.origin();
            w.push(b'M');
            for v in [g.resolution(), x0, y0] {
                w.extend_from_slice(&v.to_le_bytes());
            }
            w.extend_from_slice(&(nx as u32).to_le_bytes());
            w.extend_from_slice(&(ny as u32).to_le_bytes());
            w.extend_from_slice(&top_max.to_le_bytes());
            w.extend_from_slice(&g.volume().to_le_bytes());
            let runs: Vec<(u32, [f32; 2])> = spans.chunk_by(|a, b| a == b).map(|r| (r.len() as u32, r[0])).collect();
            w.extend_from_slice(&(runs.len() as u32).to_le_bytes());
            for (n, [b, t]) in runs {
                w.extend_from_slice(&n.to_le_bytes());
                w.extend_from_slice(&b.to_le_bytes());
                w.extend_from_slice(&t.to_le_bytes());
            }
            w.extend_from_slice(&(extra.len() as u32).to_le_bytes());
            for (k, list) in extra {
                w.extend_from_slice(&k.to_le_bytes());
                w.extend_from_slice(&(list.len() as u32).to_le_bytes());
                for [b, t] in list {
                    w.extend_from_slice(&b.to_le_bytes());
                    w.extend_from_slice(&t.to_le_bytes());
                }
            }
            let runs: Vec<(u32, u8)> = marks.chunk_by(|a, b| a == b).map(|r| (r.len() as u32, r[0])).collect();
            w.extend_from_slice(&(runs.len() as u32).to_le_bytes());
            for (n, m) in runs {
                w.extend_from_slice(&n.to_le_bytes());
                w.push(m);
            }
        }
        Stock::Turning(p) => {
            let (z0, n) = p.extent();
            w.push(b'T');
            for v in [p.resolution(), z0] {
                w.extend_from_slice(&v.to_le_bytes());
            }
            w.extend_from_slice(&(n as u32).to_le_bytes());
            w.extend_from_slice(&p.volume().to_le_bytes());
            for side in [0, 1] {
                let radii: Vec<f64> = (0..n).map(|k| if side == 0 { p.radii(k).0 } else { p.radii(k).1 }).collect();
                let runs: Vec<(u32, f64)> = radii.chunk_by(|a, b| a == b).map(|r| (r.len() as u32, r[0])).collect();
                w.extend_from_slice(&(runs.len() as u32).to_le_bytes());
                for (n, r) in runs {
                    w.extend_from_slice(&n.to_le_bytes());
                    w.extend_from_slice(&r.to_le_bytes());
                }
            }
        }
    }
    base64(&w)
}

/// The stock of `text` written in `format`; `Err` says what does not fit.
pub fn decode(format: u32, text: &str) -> Result<Stock, String> {
    if format != FORMAT {
        return Err(format!("saved stock format {format}: this server reads format {FORMAT}"));
    }
    let bytes = unbase64(text)?;
    let mut r = Reader { bytes: &bytes, at: 0 };
    let stock = match r.take(1)?[0] {
        b'M' => {
            let (res, x0, y0) = (r.f64()?, r.f64()?, r.f64()?);
            let (nx, ny) = (r.u32()? as usize, r.u32()? as usize);
            let (top_max, volume) = (r.f64()?, r.f64()?);
            if nx.saturating_mul(ny) > MAX_CELLS || res.is_nan() || res < super::MIN_RESOLUTION {
                return Err("the saved stock's grid is out of range".into());
            }
            let mut spans = Vec::with_capacity(nx * ny);
            for _ in 0..r.u32()? {
                let (n, b, t) = (r.u32()? as usize, r.f32()?, r.f32()?);
                if spans.len() + n > nx * ny {
                    return Err("the saved stock has more cells than its grid".into());
                }
                spans.extend(std::iter::repeat_n([b, t], n));
            }
            let mut extra = BTreeMap::new();
            for _ in 0..r.u32()? {
                let (k, n) = (r.u32()?, r.u32()? as usize);
                let list = (0..n).map(|_| Ok([r.f32()?, r.f32()?])).collect::<Result<Vec<_>, String>>()?;
                extra.insert(k, list);
            }
            let mut marks = Vec::with_capacity(nx * ny);
            for _ in 0..r.u32()? {
                let (n, m) = (r.u32()? as usize, r.take(1)?[0]);
                if marks.len() + n > nx * ny {
                    return Err("the saved stock has more pens than cells".into());
                }
                marks.extend(std::iter::repeat_n(m, n));
            }
            Stock::Milling(DexelGrid::from_raw(res, x0, y0, nx, ny, spans, extra, top_max, volume, marks)?)
        }
        b'T' => {
            let (res, z0) = (r.f64()?, r.f64()?);
            let n = r.u32()? as usize;
            let volume = r.f64()?;
            if n > MAX_CELLS || res.is_nan() || res < super::MIN_RESOLUTION {
                return Err("the saved profile is out of range".into());
            }
            let mut sides = [Vec::new(), Vec::new()];
            for side in &mut sides {
                for _ in 0..r.u32()? {
                    let (len, radius) = (r.u32()? as usize, r.f64()?);
                    if side.len() + len > n {
                        return Err("the saved profile has more slabs than it names".into());
                    }
                    side.extend(std::iter::repeat_n(radius, len));
                }
                if side.len() != n {
                    return Err("the saved profile has fewer slabs than it names".into());
                }
            }
            let [outer, inner] = sides;
            Stock::Turning(Profile::from_raw(res, z0, outer, inner, volume)?)
        }
        other => return Err(format!("saved stock of unknown kind {other}")),
    };
    if r.at != bytes.len() {
        return Err("the saved stock has bytes beyond its end".into());
    }
    Ok(stock)
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let s = self.bytes.get(self.at..self.at + n).ok_or("the saved stock ends early")?;
        self.at += n;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn f32(&mut self) -> Result<f32, String> {
        Ok(f32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().unwrap()))
    }
}

const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// `bytes` as standard base64 with padding (RFC 4648): the checkpoint's text and the
/// stream's tile meshes.
pub fn base64(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n =
            (u32::from(c[0]) << 16) | (u32::from(*c.get(1).unwrap_or(&0)) << 8) | u32::from(*c.get(2).unwrap_or(&0));
        for i in 0..4 {
            if i <= c.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn unbase64(text: &str) -> Result<Vec<u8>, String> {
    let text = text.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for &ch in text {
        let v = ALPHABET.iter().position(|&a| a == ch).ok_or("the saved stock is not base64")? as u32;
        acc = (acc << 6) | v;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};
    use crate::stock::cutter::Cutter;

    #[test]
    fn base64_round_trips_every_length() {
        for n in 0..10u8 {
            let bytes: Vec<u8> = (0..n).map(|i| i.wrapping_mul(97)).collect();
            assert_eq!(unbase64(&base64(&bytes)).unwrap(), bytes);
        }
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
    }

    #[test]
    fn a_cut_milling_stock_and_a_turned_one_come_back_equal() {
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        let mut s = Stock::new(&blank, &Placement::default(), false, 0.5).unwrap();
        s.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]);
        if let Stock::Milling(g) = &mut s {
            g.remove_band(3, 3, -6.0, -4.0);
        }
        assert_eq!(decode(FORMAT, &encode(&s)).unwrap(), s);
        let tube = Blank { shape: Shape::Tube { outer: 50.0, inner: 30.0 }, top: 0.0, bottom: -10.0 };
        let t = Stock::new(&tube, &Placement::default(), true, 0.25).unwrap();
        assert_eq!(decode(FORMAT, &encode(&t)).unwrap(), t);
        // A plate of 400 equal cells codes as one run: 1 + 24 + 8 + 16 + 4 + 12 + 4 bytes and
        // one run of pens, 4 + 5.
        let plain = Stock::new(&blank, &Placement::default(), false, 0.5).unwrap();
        assert_eq!(encode(&plain).len(), 78usize.div_ceil(3) * 4);
        assert!(decode(2, "").unwrap_err().contains("format 2"));
        assert!(decode(FORMAT, "TQ==").unwrap_err().contains("ends early"));
    }
}
