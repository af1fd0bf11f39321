// The program the channel runs (or ran last), whoever started it: a REST run, Execute here or
// in another browser, MDA, a swivel, a restart that resumed it. Every panel that shows a
// program (program display, header, progress, 3D path) reads it from here, never from the
// browser's own selection while the server has one.
//
// The text is never loaded whole: lines come from GET .../active-program in chunks, of which
// at most MAX_CHUNKS are kept (a CAM program of 2,000,000 blocks costs the same memory as a
// short one). The state's `program_serial` says when the program is another one.

import { api } from "../api/client";
import type { ActiveProgramRange, OpMode, State } from "../api/types";
import { Emitter } from "../core/emitter";
import type { SessionController } from "../core/session";

const CHUNK = 250; // lines per request
const MAX_CHUNKS = 48; // chunks kept: 12,000 lines at most in memory

export interface ActiveMeta {
  serial: number;
  name: string | null;
  mode: OpMode;
  sha256: string;
  lineCount: number;
}

/** Lines of one program text (the main program, or a subprogram by name). */
interface TextKey {
  serial: number;
  program: string | null;
}

class ActiveProgramStore extends Emitter<{ change: ActiveMeta | null; lines: void }> {
  meta: ActiveMeta | null = null;
  private session: SessionController | null = null;
  private chunks = new Map<string, string[]>();
  private loading = new Set<string>();
  /** Line counts of subprograms seen, by name. */
  private subCounts = new Map<string, number>();
  private wantedSerial = -1;
  private generation = 0;

  attach(session: SessionController): void {
    this.session = session;
    session.on("session", () => this.reset());
    // After a reconnect (a restarted server counts its serials afresh) the next state reloads.
    session.on("reconnected", () => (this.wantedSerial = -1));
    session.on("sample", (st) => this.sample(st));
  }

  /** Line counts of a subprogram once one of its ranges has been read. */
  lineCount(program: string | null): number | null {
    if (!program) return this.meta?.lineCount ?? null;
    return this.subCounts.get(program) ?? null;
  }

  /** Line `n` (1-based) if it is at hand; otherwise fetches its chunk and emits `lines` later. */
  line(key: TextKey, n: number): string | undefined {
    const first = Math.floor((n - 1) / CHUNK) * CHUNK + 1;
    const id = `${key.serial}|${key.program ?? ""}|${first}`;
    const chunk = this.chunks.get(id);
    if (chunk) {
      // Most recently used last: the Map's order is the eviction order.
      this.chunks.delete(id);
      this.chunks.set(id, chunk);
      return chunk[n - first];
    }
    void this.fetch(key, first, id);
    return undefined;
  }

  private async fetch(key: TextKey, first: number, id: string): Promise<void> {
    const sessionId = this.session?.id;
    if (!sessionId || this.loading.has(id)) return;
    const generation = this.generation;
    this.loading.add(id);
    try {
      const r = await api.activeProgram(sessionId, first, CHUNK, key.program);
      if (generation !== this.generation) return;
      if (r.serial !== key.serial) {
        // Another program was loaded meanwhile: take it over.
        this.take(r);
        return;
      }
      if (key.program) this.subCounts.set(key.program, r.program_line_count);
      this.chunks.set(id, r.lines);
      while (this.chunks.size > MAX_CHUNKS) this.chunks.delete(this.chunks.keys().next().value!);
      this.emit("lines", undefined);
    } catch {
      // A subprogram no longer on the stack, or the server away: asked again when needed.
    } finally {
      this.loading.delete(id);
    }
  }

  private reset(): void {
    this.generation++;
    this.meta = null;
    this.wantedSerial = -1;
    this.chunks.clear();
    this.subCounts.clear();
    this.emit("change", null);
  }

  private sample(st: State): void {
    const serial = st.program_serial ?? 0;
    if (serial === this.wantedSerial) return;
    this.wantedSerial = serial;
    if (serial === 0) {
      // No program loaded on this channel (yet): nothing to ask the server for.
      this.generation++;
      this.meta = null;
      this.chunks.clear();
      this.subCounts.clear();
      this.emit("change", null);
      return;
    }
    void this.reload();
  }

  /** Reads the loaded program's name and size again (a new program, or after a reconnect). */
  async reload(): Promise<void> {
    const id = this.session?.id;
    if (!id) return;
    const generation = ++this.generation;
    try {
      const r = await api.activeProgram(id, 1, CHUNK);
      if (generation !== this.generation) return;
      this.take(r);
    } catch (e) {
      if (generation !== this.generation) return;
      if ((e as { status?: number }).status === 404) {
        this.meta = null;
        this.chunks.clear();
        this.emit("change", null);
      }
    }
  }

  private take(r: ActiveProgramRange): void {
    const same = this.meta && this.meta.serial === r.serial && this.meta.sha256 === r.sha256;
    if (!same) {
      this.chunks.clear();
      this.subCounts.clear();
    }
    this.meta = { serial: r.serial, name: r.name, mode: r.mode, sha256: r.sha256, lineCount: r.line_count };
    this.wantedSerial = r.serial;
    if (r.program === null && r.from === 1) this.chunks.set(`${r.serial}||1`, r.lines);
    this.emit("change", this.meta);
  }
}

export const activeProgram = new ActiveProgramStore();

/** The name a display gives the active program. */
export function activeName(meta: ActiveMeta | null): string {
  if (!meta) return "–";
  if (meta.mode === "MDA") return "MDA";
  return meta.name ?? "(unnamed program)";
}
