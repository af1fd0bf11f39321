// The session tokens this browser knows (a server started with `--auth required` wants one on
// every request to a session). Kept in localStorage by session id: the owner's tokens from
// creating a session, or one token from a shared link (?session=ID&token=...).

export type Role = "owner" | "operator" | "observer";
export type Tokens = Partial<Record<Role, string>>;

const PREFIX = "nctwin.tokens.";

export function tokensOf(id: string): Tokens {
  try {
    const raw = localStorage.getItem(PREFIX + id);
    return raw ? (JSON.parse(raw) as Tokens) : {};
  } catch {
    return {};
  }
}

/** The strongest token known for a session (the one requests present). */
export function tokenFor(id: string): string | undefined {
  const t = tokensOf(id);
  return t.owner ?? t.operator ?? t.observer;
}

export function rememberTokens(id: string, tokens: Tokens): void {
  try {
    localStorage.setItem(PREFIX + id, JSON.stringify({ ...tokensOf(id), ...tokens }));
  } catch {
    // storage unavailable: the tokens live as long as the page
  }
}

/** A token given without its role (from a link): kept as the weakest role until the server tells. */
export function rememberToken(id: string, token: string): void {
  const known = tokensOf(id);
  if (Object.values(known).includes(token)) return;
  try {
    localStorage.setItem(PREFIX + id, JSON.stringify({ observer: token }));
  } catch {
    // as above
  }
}

export function forgetTokens(id: string): void {
  try {
    localStorage.removeItem(PREFIX + id);
  } catch {
    // as above
  }
}

/** The session id a REST path addresses ("/sessions/s1/state" -> "s1"), if any. */
export function sessionOfPath(path: string): string | null {
  const m = /^\/sessions\/([^/?]+)/.exec(path);
  return m ? decodeURIComponent(m[1]!) : null;
}
