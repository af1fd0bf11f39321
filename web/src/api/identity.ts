// Who uses this page: the display name typed on the start page (kept in localStorage, sent as
// `nctwin-user` with every request so the action log can say who did what) and whether the page
// only watches (a watch link, `?view=watch`: the server refuses its commands as an observer's,
// also with `--auth off`, and the screen disables its controls).

const NAME_KEY = "nctwin.displayName";

let watching = new URLSearchParams(location.search).get("view") === "watch";

/** The display name (empty until the user types one). */
export function displayName(): string {
  try {
    return localStorage.getItem(NAME_KEY) ?? "";
  } catch {
    return "";
  }
}

export function setDisplayName(name: string): void {
  try {
    localStorage.setItem(NAME_KEY, name.trim().slice(0, 40));
  } catch {
    // private mode: the name lasts for this page only
  }
}

/** Whether this page only watches its session. */
export function viewOnly(): boolean {
  return watching;
}

/** Switches watching on or off (joining from the start page, or following a watch link). */
export function setViewOnly(on: boolean): void {
  watching = on;
  const url = new URL(location.href);
  if (on) url.searchParams.set("view", "watch");
  else url.searchParams.delete("view");
  history.replaceState(null, "", url);
}

/** The identity headers of a request. */
export function identityHeaders(): Record<string, string> {
  const headers: Record<string, string> = {};
  const name = displayName();
  if (name) headers["nctwin-user"] = encodeURIComponent(name);
  if (watching) headers["nctwin-view-only"] = "1";
  return headers;
}
