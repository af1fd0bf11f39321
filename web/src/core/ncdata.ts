// Reads NC data text ("$MA_POS_LIMIT_PLUS[X]=500.") into a lookup table, for what the screen
// needs to know about a machine (travel ranges, rotary axes, tool lengths). Lenient: lines it
// does not understand are skipped; the server is the one that validates.

export class NcData {
  private readonly values = new Map<string, string>();

  constructor(text: string) {
    for (const raw of text.split("\n")) {
      const line = raw.replace(/;.*$/, "").trim();
      const m = /^(\$[A-Z0-9_]+)(?:\[([^\]]*)\])?\s*=\s*(.+)$/i.exec(line);
      if (!m) continue;
      const [, name = "", index = "", value = ""] = m;
      this.values.set(key(name, index), value.trim());
    }
  }

  /** The raw value of `$NAME[index]` (index like "X" or "1,1"; "" for none). */
  raw(name: string, index = ""): string | undefined {
    return this.values.get(key(name, index));
  }

  number(name: string, index = ""): number | undefined {
    const v = this.raw(name, index);
    if (v === undefined) return undefined;
    const n = Number(v);
    return Number.isFinite(n) ? n : undefined;
  }

  /** Axial machine data, indexed by machine axis name or by AXn (n from 1). */
  axisNumber(name: string, axis: string, axisNo: number): number | undefined {
    return this.number(name, axis) ?? this.number(name, `AX${axisNo}`);
  }

  axisFlag(name: string, axis: string, axisNo: number): boolean {
    const v = this.raw(name, axis) ?? this.raw(name, `AX${axisNo}`);
    return v !== undefined && /^(TRUE|1)$/i.test(v);
  }
}

function key(name: string, index: string): string {
  return `${name.toUpperCase()}[${index.replace(/\s+/g, "").toUpperCase()}]`;
}
