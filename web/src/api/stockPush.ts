// The stream's `stock` message (server: api/stock_tiles.rs `StockTilesMessage`): the tiles a
// cut changed from version `since` to `version`, the meshes of the first few inline (binary STL
// as base64), the others to fetch with GET .../stock/tiles/{i}/{j}. `reload`: the client's
// version cannot be brought up to date from the kept steps: fetch .../stock/changes?since=0.

export interface StockPush {
  type: "stock";
  version: number;
  since: number;
  reload: boolean;
  tile_cells: number;
  tiles: [number, number][];
  pens: { pen: number; t: number; d: number }[];
  meshes: { i: number; j: number; stl: string }[];
}

/** The bytes of standard base64 text. */
export function fromBase64(text: string): ArrayBuffer {
  const raw = atob(text);
  const bytes = new Uint8Array(raw.length);
  for (let k = 0; k < raw.length; k++) bytes[k] = raw.charCodeAt(k);
  return bytes.buffer;
}
