//! Program and NC data files as bytes → text: UTF-8 (with or without a byte order mark),
//! UTF-16 with a byte order mark, and legacy 8-bit encodings (Windows-1252/Latin-1, Windows-1251
//! or KOI8 Cyrillic, GBK Chinese, ...) guessed by `chardetng` and decoded by `encoding_rs`.
//!
//! NC words are ASCII in every one of these encodings, so only comments, `MSG` texts and
//! strings depend on the guess. A file is refused (never guessed at) when its bytes do not decode
//! without replacement characters or hold control characters no text file has (NUL and the
//! like): a binary file, or a file in an encoding the guess got wrong.

use encoding_rs::{Encoding, UTF_8};

/// A decoded file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decoded {
    pub text: String,
    /// The encoding's name as `encoding_rs` spells it (`UTF-8`, `windows-1251`, `GBK`, ...).
    pub encoding: &'static str,
}

/// Decodes a file's bytes; `Err` names why they are not text.
pub fn decode(bytes: &[u8]) -> Result<Decoded, String> {
    let (encoding, body) = match Encoding::for_bom(bytes) {
        Some((encoding, bom)) => (encoding, &bytes[bom..]),
        None if std::str::from_utf8(bytes).is_ok() => (UTF_8, bytes),
        None => {
            let mut detector = chardetng::EncodingDetector::new(chardetng::Iso2022JpDetection::Deny);
            detector.feed(bytes, true);
            (detector.guess(None, chardetng::Utf8Detection::Deny), bytes)
        }
    };
    let text = encoding
        .decode_without_bom_handling_and_without_replacement(body)
        .ok_or_else(|| format!("not decodable as {} (the encoding guessed)", encoding.name()))?;
    if let Some((at, c)) = text.char_indices().find(|&(_, c)| is_binary(c)) {
        return Err(format!("not a text file: control character U+{:04X} at byte {at}", c as u32));
    }
    Ok(Decoded { text: text.into_owned(), encoding: encoding.name() })
}

/// Characters no program or data file holds: C0 controls other than TAB, LF, FF, CR and the
/// old end-of-file mark SUB, DEL, and the C1 controls (what undefined bytes of single-byte code
/// pages decode to).
fn is_binary(c: char) -> bool {
    matches!(c, '\0'..='\u{8}' | '\u{b}' | '\u{e}'..='\u{19}' | '\u{1b}'..='\u{1f}' | '\u{7f}'..='\u{9f}')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_and_its_byte_order_mark_decode_as_utf8() {
        let d = decode("G1 X1 ; Prüfung\r\nM30\r\n".as_bytes()).unwrap();
        assert_eq!((d.text.as_str(), d.encoding), ("G1 X1 ; Prüfung\r\nM30\r\n", "UTF-8"));
        let d = decode(b"\xEF\xBB\xBFG0 X1\n").unwrap();
        assert_eq!(d.text, "G0 X1\n");
    }

    #[test]
    fn legacy_code_pages_are_guessed() {
        let (bytes, _, _) = encoding_rs::WINDOWS_1251.encode(
            "; Программа обработки фланца\nMSG(\"Установите заготовку и проверьте инструмент\")\nG0 X10\nM30\n",
        );
        let d = decode(&bytes).unwrap();
        assert_eq!(d.encoding, "windows-1251");
        assert!(d.text.contains("Установите заготовку"), "{}", d.text);
        let (bytes, _, _) = encoding_rs::GBK.encode("; 加工程序 法兰盘\nMSG(\"请安装毛坯并检查刀具\")\nG0 X10\nM30\n");
        let d = decode(&bytes).unwrap();
        assert_eq!(d.encoding, "GBK");
        assert!(d.text.contains("请安装毛坯并检查刀具"), "{}", d.text);
        let (bytes, _, _) = encoding_rs::WINDOWS_1252.encode("; Außenkontur schlichten, Maße prüfen\nG0 X1\n");
        assert_eq!(decode(&bytes).unwrap().text, "; Außenkontur schlichten, Maße prüfen\nG0 X1\n");
    }

    #[test]
    fn binary_files_are_refused() {
        let e = decode(b"PK\x03\x04\x14\x00\x00\x00\x08\x00\xa3\x91").unwrap_err();
        assert!(e.starts_with("not a text file: control character U+0003"), "{e}");
        assert!(decode(b"G0 X1\n\0\0\0").is_err());
    }
}
