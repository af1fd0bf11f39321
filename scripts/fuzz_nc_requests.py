#!/usr/bin/env python3
"""NC-aware requests for the bad-input campaign (scripts/fuzz-api.sh): what schemathesis's random
strings rarely reach. Sessions are created with machine data that resize the synchronized
actions' memory and the fast I/O (MD28250..28258, MD10300..10360), programs of the newer language
(CIP, CT, EXECSTRING, TOFFR, SCC, ANG, synchronized actions, splines, CYCLE832) are run, checked,
previewed and given as MDA, and while they run the I/O (`PUT .../io`) and the machine data are
changed with numbers in range, at the edges, huge, negative and not numbers at all.

Fails on any 5xx, on a request not answered within its timeout and on a server that stops
answering. Standard library only; a fixed seed unless FUZZ_SEED=random.

    scripts/fuzz_nc_requests.py http://127.0.0.1:8080 [rounds]
"""
import json
import os
import random
import sys
import urllib.error
import urllib.request

NUMBERS = ["0", "-0", "1", "5", "-5", "10", "45", "90", "360", "0.001", "1EX9", "-1EX9", "1EX300", "1e9",
           "99999999", "1/0", "SQRT(-1)", "1EX300*1EX300", "LN(0)", "ACOS(2)", "R1", "R1/R2"]
INDICES = ["0", "1", "2", "7", "8", "16", "40", "41", "50", "255", "99999999999", "-1", "1.5", "R1"]
AXES = ["X", "Y", "Z", "A", "C", "Q", "SP1", ""]
CONDITIONS = ["$AA_IM[{a}]>{n}", "$AC_TIME>{n}", "$A_IN[{i}]==1", "$A_INA[{i}]>{n}", "$AC_MARKER[{i}]>{n}",
              "TRUE", "1/0>1"]
ACTIONS = ["$AC_MARKER[{i}]={n}", "$AC_PARAM[{i}]={n}/$AC_PARAM[{i}]", "$AC_PARAM[{i}]=BOUND({n},{n},{n})",
           "$A_OUT[{i}]=1", "$A_OUTA[{i}]={n}", "$AC_OVR={n}", "DELDTG", "POS[{a}]={n} FA[{a}]={n}",
           "CANCEL({i})", "NOSUCH", "$AA_OFF[{a}]={n}"]
BLOCKS = [
    "G1 X={n} Y={n} F1000", "G0 X={n} Z={n}", "CIP X={n} Y={n} I1={n} J1={n}", "CIP X20 Y20 I1=10 J1=10",
    "CIP X0 Y0 I1=0 J1=0", "CT X={n} Y={n}", "ANG={n}", "X={n} Y={n} ANG={n}", "ANG=45\nX40 Y10 ANG=45",
    "EXECSTRING(\"G1 X={n} F500\")", "EXECSTRING(\"G1 X5 F500)", "EXECSTRING(STR_A)", "STR_A=\"EXECSTRING(STR_A)\"",
    "STR_A=\"G1 X\" << {n}", "TOFFR={n}", "G96 S={n} LIMS={n} SCC[{a}] M3", "ID={i} WHEN {c} DO {d}",
    "IDS={i} WHENEVER {c} DO {d}", "ID={i} EVERY {c} DO {d}", "ID={i} FROM {c} DO {d}", "DO {d}",
    "ASPLINE X={n} Y={n}", "BSPLINE X={n} SD={n}", "POLY PO[X]=({n},{n}) PL={n}", "CYCLE832({n},_ROUGH,1)",
    "DRIVE", "SOFT", "G643", "G642", "STOPRE", "$A_OUT[{i}]=1", "R3=$A_INA[{i}]", "R3=$A_OUTA[{i}]",
    "R3=$AC_PARAM[{i}]", "R3=$AC_MARKER[{i}]", "R3=$AC_TIMER[{i}]", "SUB1",
]
MACHINE_DATA = ["$MC_MM_NUM_SYNC_ELEMENTS={v}", "$MC_MM_NUM_AC_PARAM={v}", "$MC_MM_NUM_AC_MARKER={v}",
                "$MC_MM_NUM_AC_TIMER={v}", "$MN_FASTIO_ANA_NUM_INPUTS={v}", "$MN_FASTIO_ANA_NUM_OUTPUTS={v}",
                "$MN_FASTIO_DIG_NUM_INPUTS={v}", "$MN_FASTIO_DIG_NUM_OUTPUTS={v}", "$MC_MM_NUM_FCTDEF_ELEMENTS={v}"]
MD_VALUES = ["0", "1", "5", "8", "9", "159", "20000", "20001", "32000", "99999999999999999999", "-1", "1.5",
             "1e309", "NaN", "\"X\"", ""]
MACHINES = ["mill-3axis", "lathe-2axis", "mill5-table-ac"]


class Failure(Exception):
    pass


def request(base, method, path, body=None, raw=None, timeout=120):
    data = raw if raw is not None else (json.dumps(body).encode() if body is not None else None)
    req = urllib.request.Request(base + path, data=data, method=method)
    if data is not None:
        req.add_header("Content-Type", "application/json")
    try:
        with urllib.request.urlopen(req, timeout=timeout) as reply:
            status, text = reply.status, reply.read()
    except urllib.error.HTTPError as e:
        status, text = e.code, e.read()
    except (urllib.error.URLError, ConnectionError, TimeoutError) as e:
        raise Failure(f"{method} {path}: no answer ({e}) to {(raw or data or b'')[:400]!r}")
    if status >= 500:
        raise Failure(f"{method} {path}: {status} {text[:400]!r} for {(raw or data or b'')[:2000]!r}")
    # A session ends only when it is deleted: an engine that panicked ends it too (the server
    # then answers 404 "has ended"), which is a crash all the same.
    if status == 404 and b"has ended" in text and method != "DELETE":
        raise Failure(f"{method} {path}: the session ended (the engine panicked?) for {(raw or data or b'')[:2000]!r}")
    try:
        return status, json.loads(text) if text else None
    except ValueError:
        return status, None


def fill(rng, template):
    out, rest = [], template
    while "{" in rest:
        start = rest.index("{")
        end = rest.index("}", start)
        out.append(rest[:start])
        key = rest[start + 1:end]
        out.append({
            "n": lambda: rng.choice(NUMBERS),
            "i": lambda: rng.choice(INDICES),
            "a": lambda: rng.choice(AXES),
            "c": lambda: fill(rng, rng.choice(CONDITIONS)),
            "d": lambda: fill(rng, rng.choice(ACTIONS)),
        }[key]())
        rest = rest[end + 1:]
    return "".join(out) + rest


def program(rng):
    lines = [fill(rng, rng.choice(BLOCKS)) for _ in range(rng.randint(1, 10))]
    return "DEF STRING[60] STR_A\nG17 G90 G1 F1000\n" + "\n".join(lines) + "\nM30\n"


def io_body(rng):
    """A `PUT .../io` body: JSON the schema allows and JSON it does not (raw bytes)."""
    signal = rng.choice([0, 1, 8, 40, 41, 2**31 - 1, 2**31, 2**63, -1])
    value = rng.choice(["1", "0", "-5", "1e308", "1e400", "-1e400", "NaN", "Infinity", "true", "\"x\"", "null"])
    return rng.choice([
        '{"inputs":[{"signal":%d,"value":%s}]}' % (signal, rng.choice(["true", "false", "1", "null"])),
        '{"outputs":[{"signal":%d,"value":true}]}' % signal,
        '{"analog_inputs":[{"signal":%d,"value":%s}]}' % (signal, value),
        '{"plc_data":[{"offset":%d,"bytes":[%s]}]}' % (signal, ",".join(str(rng.choice([0, 255, 256, -1, 2**31, 2**40])) for _ in range(rng.randint(0, 5)))),
        '{"plc_data":[{"offset":%d,"bytes":[%s]}]}' % (rng.choice([0, 1, 1000, 2**31 - 1, 2**32]), ",".join(["1"] * rng.choice([1, 1000, 70000]))),
        '{"inputs":[' + ",".join('{"signal":%d,"value":true}' % rng.randint(0, 50) for _ in range(rng.randint(0, 60))) + "]}",
    ]).encode()


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    base = sys.argv[1].rstrip("/") + "/api/v1"
    rounds = int(sys.argv[2]) if len(sys.argv) == 3 else 40
    seed = os.environ.get("FUZZ_SEED", "20261127")
    rng = random.Random(None if seed == "random" else int(seed))
    sent = 0
    for r in range(rounds):
        md = "\n".join(rng.choice(MACHINE_DATA).replace("{v}", rng.choice(MD_VALUES)) for _ in range(rng.randint(0, 3)))
        status, session = request(base, "POST", "/sessions", {"machine": rng.choice(MACHINES), "machine_data": md})
        sent += 1
        if status != 201:
            status, session = request(base, "POST", "/sessions", {"machine": rng.choice(MACHINES)})
            sent += 1
        s = f"/sessions/{session['id']}"
        request(base, "PUT", s + "/programs/SUB1", {"text": "PROC SUB1\n" + fill(rng, rng.choice(BLOCKS)) + "\nSUB1\nM17\n"})
        for _ in range(6):
            text = program(rng)
            choice = rng.randrange(6)
            if choice == 0:
                request(base, "POST", s + "/check", {"program": text})
            elif choice == 1:
                request(base, "POST", s + "/preview", {"program": text})
            elif choice == 2:
                request(base, "POST", s + "/mda", {"program": fill(rng, rng.choice(BLOCKS)), "pace": "fast", "wait": True})
            else:
                request(base, "POST", s + "/run", {"program": text, "pace": rng.choice(["fast", "realtime"]), "wait": rng.random() < 0.5})
            for _ in range(rng.randint(0, 3)):
                request(base, "PUT", s + "/io", raw=io_body(rng))
                sent += 1
            if rng.random() < 0.3:
                md = rng.choice(MACHINE_DATA).replace("{v}", rng.choice(MD_VALUES))
                request(base, "PUT", s + "/machine-data", {"text": md})
                sent += 1
            request(base, "GET", s + "/state")
            request(base, "GET", s + "/io")
            request(base, "POST", s + "/reset")
            sent += 5
        request(base, "DELETE", s)
        status, _ = request(base, "GET", "/health")
        if status != 200:
            raise Failure(f"/health answers {status} after round {r}")
    print(f"==> NC requests: {rounds} sessions, {sent} requests, no 5xx, every request answered")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
