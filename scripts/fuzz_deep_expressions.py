#!/usr/bin/env python3
"""Deep and long expressions in every field that takes program text (issue 20): the step of the
bad-input campaign (scripts/fuzz-api.sh) that schemathesis cannot generate. Each attack is
thousands of levels deep (nested parentheses, unary operators, calls, R[R[..., a 30,000-term
sum, mixes of them) and goes to /check, /preview, /search, /mda, /run, PUT programs/{name} and,
as NC data text, to machine data, kinematic chains and a new session's machine data.

Fails on any 5xx, on a server that stops answering, and on a program endpoint that does not
name alarm 12080 (diagnostics, `errors` of a 400, or the state's alarms). Standard library only.

    scripts/fuzz_deep_expressions.py http://127.0.0.1:8080
"""
import json
import sys
import urllib.error
import urllib.request

N = 5_000  # levels of each nesting attack: far beyond the parser's 128
TERMS = 30_000  # terms of the flat chains


def nested(open_, inner, close):
    return open_ * N + inner + close * N


ATTACKS = {
    "parentheses": "R1=" + nested("(", "1", ")"),
    "unary minus": "R1=" + "-" * N + "1",
    "unary plus": "R1=" + "+" * N + "1",
    "NOT": "R1=" + "NOT " * N + "TRUE",
    "B_NOT": "R1=" + "B_NOT " * N + "1",
    "SIN(SIN(": "R1=" + nested("SIN(", "0", ")"),
    "ATAN2(1,": "R1=" + nested("ATAN2(1,", "0", ")"),
    "R[R[": "R1=" + nested("R[", "1", "]"),
    "index": "R[" + nested("(", "1", ")") + "]=1",
    "flat sum": "R1=" + "+".join(["1"] * TERMS),
    "flat product": "R1=" + "*".join(["1"] * TERMS),
    "string concatenation": "IF " + "<<".join(['"A"'] * TERMS) + '=="A"',
    "frame chain": "$P_PFRAME=" + ":".join(["CTRANS()"] * TERMS),
    "mixed": "R1=" + nested("(-SIN(R[NOT ", "1", "]))"),
    "condition": "WHILE " + nested("(", "1", ")"),
    "axis word": "G1 X=" + nested("(", "1", ")") + " F100",
}


class Failure(Exception):
    pass


def request(base, method, path, body=None, content_type="application/json"):
    data = None
    if body is not None:
        data = body.encode() if isinstance(body, str) else json.dumps(body).encode()
    req = urllib.request.Request(base + path, data=data, method=method)
    if data is not None:
        req.add_header("Content-Type", content_type)
    try:
        with urllib.request.urlopen(req, timeout=60) as reply:
            status, raw = reply.status, reply.read()
    except urllib.error.HTTPError as e:
        status, raw = e.code, e.read()
    except (urllib.error.URLError, ConnectionError, TimeoutError) as e:
        raise Failure(f"{method} {path}: no answer ({e}): the server died?")
    try:
        return status, json.loads(raw) if raw else None
    except ValueError:
        return status, None


def alarms_in(body):
    """Every (alarm, line) the body names: diagnostics, a 400's errors, the state's alarms."""
    if not isinstance(body, dict):
        return []
    found = [(d.get("alarm"), d.get("line")) for d in body.get("diagnostics", []) + body.get("errors", [])]
    found += [(a.get("number"), a.get("line")) for a in body.get("alarms", [])]
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    base = sys.argv[1].rstrip("/") + "/api/v1"
    status, session = request(base, "POST", "/sessions", {"machine": "mill-3axis"})
    if status != 201:
        raise Failure(f"POST /sessions: {status} {session}")
    s = f"/sessions/{session['id']}"
    checked = 0
    for name, line in ATTACKS.items():
        program = f"G0 X0\n{line}\nM30\n"
        calls = [
            ("POST", "/check", {"program": program}, 2),
            ("POST", "/preview", {"program": program}, 2),
            ("POST", "/search", {"program": program, "line": 3}, 2),
            ("PUT", "/programs/DEEP", {"text": program}, 2),
            ("POST", "/mda", {"program": line, "wait": True}, 1),
            ("POST", "/run", {"program": program, "wait": True}, 2),
        ]
        for method, path, body, alarm_line in calls:
            status, reply = request(base, method, s + path, body)
            checked += 1
            if status >= 500:
                raise Failure(f"{name}: {method} {path}: {status} {reply}")
            if (12080, alarm_line) not in alarms_in(reply):
                raise Failure(f"{name}: {method} {path}: {status}, no alarm 12080 of line {alarm_line}: {reply}")
            if status == 200 and path == "/run":
                request(base, "POST", s + "/reset")
        # NC data text takes no expressions: the same text is a bad value (400), never a crash.
        data_calls = [
            ("PUT", s + "/machine-data", {"text": "$MC_AXCONF_GEOAX_NAME_TAB[0]=" + line[3:]}, "application/json"),
            ("PUT", s + "/kinematic-chains", '$NK_NAME[0]="A"\n$NK_OFF_DIR[0,0]=' + line[3:], "text/plain"),
            ("POST", "/sessions", {"machine_data": "$MN_FOO=" + line[3:]}, "application/json"),
        ]
        for method, path, body, content_type in data_calls:
            status, reply = request(base, method, path, body, content_type)
            checked += 1
            if status >= 500 or status < 400:
                raise Failure(f"{name}: {method} {path}: {status} {reply}")
        status, health = request(base, "GET", "/health")
        if status != 200:
            raise Failure(f"{name}: /health answers {status} {health}")
    print(f"==> deep expressions: {len(ATTACKS)} attacks, {checked} requests, no 5xx, alarm 12080 each time")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
