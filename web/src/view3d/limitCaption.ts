// The caption of the limit marks: how many times an axis reached its velocity and its
// acceleration limit in feed motion along the programmed path (the marks in the 3D view), with
// the first hits named in the tooltip (axis, line, value against the machine data's limit).

import type { PreviewResponse } from "../api/types";
import { byId, fmt, setText } from "../core/dom";

/** Shows the preview's limit hits in the 3D view's caption (null: none). */
export function showLimitHits(r: PreviewResponse | null): void {
  const caption = byId("view3d-limits");
  const hits = r?.limit_hits ?? [];
  const total = r?.limit_hits_total ?? hits.length;
  caption.hidden = total === 0;
  caption.dataset.velocity = String(hits.filter((h) => h.kind === "velocity").length);
  caption.dataset.acceleration = String(hits.filter((h) => h.kind === "acceleration").length);
  caption.dataset.total = String(total);
  if (total === 0) return;
  const more = total > hits.length ? ` (${total} in all)` : "";
  // Marks the server could not place on the part are drawn grey: say why.
  const inexact = hits.filter((h) => h.exact === false).length;
  caption.dataset.inexact = String(inexact);
  const grey = inexact ? `; ${inexact} grey: the table was turned by axes the machine data do not describe` : "";
  setText(
    caption,
    `axis limits: ${caption.dataset.velocity} velocity, ${caption.dataset.acceleration} acceleration${more}${grey}`,
  );
  caption.title = hits
    .slice(0, 12)
    .map((h) => {
      const unit = h.kind === "velocity" ? "/s" : "/s²";
      return `line ${h.line}: ${h.axis} ${h.kind} ${fmt(h.value, 0)}${unit} (limit ${fmt(h.limit, 0)})`;
    })
    .join("\n");
}
