//! Binary STL solids for the stock tests of the engine and of the server (which includes this
//! file by path): blanks, holders and targets of known volume.

/// A binary STL of the box `lo`..`hi` (12 triangles, outward).
pub fn box_stl(lo: [f32; 3], hi: [f32; 3]) -> Vec<u8> {
    let c = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    // Faces as corner indices, counter-clockwise from outside.
    let faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&12u32.to_le_bytes());
    for f in faces {
        for t in [[f[0], f[1], f[2]], [f[0], f[2], f[3]]] {
            out.extend_from_slice(&[0u8; 12]);
            for v in t {
                for x in c(v) {
                    out.extend_from_slice(&x.to_le_bytes());
                }
            }
            out.extend_from_slice(&[0u8; 2]);
        }
    }
    out
}
