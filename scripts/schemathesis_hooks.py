"""Schemathesis hooks for scripts/fuzz-api.sh (loaded through SCHEMATHESIS_HOOKS).

The STL uploads (`PUT .../stock.stl`, `POST .../stock/compare`) take `model/stl`, a media type
schemathesis cannot build from a schema: give it raw bytes, from noise to the 84-byte header of
an empty binary STL and a one-facet file, so those endpoints are fuzzed like the others.
"""

import struct

import schemathesis
from hypothesis import strategies as st


def _binary_stl(facets):
    body = b"".join(struct.pack("<12fH", *values, 0) for values in facets)
    return b"\0" * 80 + struct.pack("<I", len(facets)) + body


_ONE_FACET = _binary_stl([(0, 0, 1, 0, 0, 0, 10, 0, 0, 0, 10, 0)])

schemathesis.openapi.media_type(
    "model/stl",
    st.one_of(
        st.binary(max_size=1024),
        st.just(_binary_stl([])),
        st.just(_ONE_FACET),
        st.just(b"solid x\nendsolid x\n"),
    ),
)
