//! PLC data as machine-builder programs read and write them: `$A_DBB[n]` (byte), `$A_DBW[n]`
//! (word), `$A_DBD[n]` (double word), `$A_DBR[n]` (REAL), n the byte offset into the data area
//! the NCK shares with the PLC. One simulated area per session, [`PLC_DATA_BYTES`] bytes, zero
//! until written; it survives reset and restart (in the checkpoint with the R parameters,
//! `retained.rs`), as PLC memory does.
//!
//! Decisions where the manuals leave room or the simulation differs from a machine:
//! - Size 4096 bytes (decision: the excerpts at hand do not give the size; 4096 is what we
//!   recall of the control's area for PLC variables); an access beyond it: 17020.
//! - Byte order big-endian, as the S7 PLC stores words and double words, so `$A_DBW[0]=1`
//!   puts 0 in byte 0 and 1 in byte 1, the PLC's DBB1. No alignment is required.
//! - `$A_DBB` reads 0..255, `$A_DBW` −32768..32767, `$A_DBD` as a 32-bit signed number, `$A_DBR`
//!   as a 32-bit float. A write takes −128..255 / −32768..65535 / the 32-bit range (else 12560)
//!   and stores the two's complement.
//! - No PLC program runs, so only programs and the shell change the area: a write takes effect
//!   when its block is prepared and a read does not wait for the main run (on the control both
//!   follow the PLC's cycle; here nothing else would change the value in between).

use crate::alarm::Alarm;
use crate::interp::eval::value::Value;

/// Bytes of the simulated PLC data area.
pub const PLC_DATA_BYTES: usize = 4096;

/// The PLC data area: bytes up to the last one written (the rest read as 0).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PlcData(Vec<u8>);

/// True for the four PLC data names.
pub(crate) fn is_name(name: &str) -> bool {
    width(name).is_some()
}

/// The width in bytes of the access `name` makes.
fn width(name: &str) -> Option<usize> {
    Some(match name {
        "$A_DBB" => 1,
        "$A_DBW" => 2,
        "$A_DBD" | "$A_DBR" => 4,
        _ => return None,
    })
}

/// The byte offset of `name[n]`, checked against the area (17020 outside).
fn offset(name: &str, indices: &[Value], line: u32) -> Result<usize, Alarm> {
    let [n] = indices else { return Err(Alarm::index_error(line, name, "needs one byte offset")) };
    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let w = width(name).unwrap_or(1);
    usize::try_from(n)
        .ok()
        .filter(|n| n + w <= PLC_DATA_BYTES)
        .ok_or_else(|| Alarm::index_error(line, name, &format!("byte {n} (0..{})", PLC_DATA_BYTES - w)))
}

impl PlcData {
    /// The area as stored (trailing bytes never written are left out).
    pub fn bytes(&self) -> &[u8] {
        &self.0
    }

    /// An area holding `bytes` (at most [`PLC_DATA_BYTES`]; the rest is cut off).
    pub fn from_bytes(bytes: &[u8]) -> PlcData {
        let mut data = PlcData(bytes[..bytes.len().min(PLC_DATA_BYTES)].to_vec());
        data.trim();
        data
    }

    fn trim(&mut self) {
        let used = self.0.iter().rposition(|b| *b != 0).map_or(0, |i| i + 1);
        self.0.truncate(used);
    }

    fn get<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut out = [0; N];
        for (i, b) in out.iter_mut().enumerate() {
            *b = self.0.get(at + i).copied().unwrap_or(0);
        }
        out
    }

    /// Writes `bytes` at byte `at` (checked by [`write`] before).
    pub(crate) fn put(&mut self, at: usize, bytes: &[u8]) {
        let end = (at + bytes.len()).min(PLC_DATA_BYTES);
        if self.0.len() < end {
            self.0.resize(end, 0);
        }
        self.0[at..end].copy_from_slice(&bytes[..end - at]);
        self.trim();
    }

    /// `$A_DBB[n]` .. `$A_DBR[n]`; `None` for any other name.
    pub(crate) fn read(&self, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
        width(name)?;
        Some(offset(name, indices, line).map(|at| match name {
            "$A_DBB" => Value::Int(self.get::<1>(at)[0].into()),
            "$A_DBW" => Value::Int(i16::from_be_bytes(self.get(at)).into()),
            "$A_DBD" => Value::Int(i32::from_be_bytes(self.get(at)).into()),
            _ => Value::Real(f32::from_be_bytes(self.get(at)).into()),
        }))
    }
}

/// The bytes a program's `name[indices] = value` writes and where: (offset, bytes).
pub(crate) fn write(name: &str, indices: &[Value], value: &Value, line: u32) -> Result<(usize, Vec<u8>), Alarm> {
    let at = offset(name, indices, line)?;
    let out_of_range = || Alarm::value_out_of_range(line, &format!("{name}[{at}]={}", value.as_text()));
    let bytes = if name == "$A_DBR" {
        let v = value.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
        if !v.is_finite() || v.abs() > f64::from(f32::MAX) {
            return Err(out_of_range());
        }
        (v as f32).to_be_bytes().to_vec()
    } else {
        let v = value.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
        let bits = 8 * width(name).unwrap_or(1) as u32;
        if v < -(1i64 << (bits - 1)) || v >= 1i64 << bits {
            return Err(out_of_range());
        }
        let all = (v as u64).to_be_bytes();
        all[8 - bits as usize / 8..].to_vec()
    };
    Ok((at, bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_into(data: &mut PlcData, name: &str, at: i64, value: Value) {
        let (at, bytes) = write(name, &[Value::Int(at)], &value, 1).unwrap();
        data.put(at, &bytes);
    }

    fn read(data: &PlcData, name: &str, at: i64) -> Value {
        data.read(name, &[Value::Int(at)], 1).unwrap().unwrap()
    }

    #[test]
    fn words_are_big_endian_like_the_plc() {
        let mut data = PlcData::default();
        // 0x1234 = 4660: byte 10 holds 0x12 = 18, byte 11 0x34 = 52.
        write_into(&mut data, "$A_DBW", 10, Value::Int(4660));
        assert_eq!(read(&data, "$A_DBB", 10), Value::Int(18));
        assert_eq!(read(&data, "$A_DBB", 11), Value::Int(52));
        // -2 as a word is 0xFFFE; its high byte reads 255.
        write_into(&mut data, "$A_DBW", 20, Value::Int(-2));
        assert_eq!(read(&data, "$A_DBW", 20), Value::Int(-2));
        assert_eq!(read(&data, "$A_DBB", 20), Value::Int(255));
        // 1.5 as an IEEE single is 0x3FC00000.
        write_into(&mut data, "$A_DBR", 100, Value::Real(1.5));
        assert_eq!(read(&data, "$A_DBB", 100), Value::Int(0x3F));
        assert_eq!(read(&data, "$A_DBD", 100), Value::Int(0x3FC0_0000));
        assert_eq!(read(&data, "$A_DBR", 100), Value::Real(1.5));
    }

    #[test]
    fn accesses_stay_inside_the_area_and_values_inside_their_width() {
        let data = PlcData::default();
        assert_eq!(read(&data, "$A_DBD", 4092), Value::Int(0));
        assert_eq!(data.read("$A_DBD", &[Value::Int(4093)], 3).unwrap().unwrap_err().number, 17020);
        assert_eq!(data.read("$A_DBB", &[Value::Int(-1)], 3).unwrap().unwrap_err().number, 17020);
        assert_eq!(write("$A_DBB", &[Value::Int(0)], &Value::Int(256), 3).unwrap_err().number, 12560);
        assert_eq!(write("$A_DBB", &[Value::Int(0)], &Value::Int(-129), 3).unwrap_err().number, 12560);
        assert!(write("$A_DBW", &[Value::Int(0)], &Value::Int(65535), 3).is_ok());
    }
}
