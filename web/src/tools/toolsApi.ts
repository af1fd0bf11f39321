// The session's tool list over REST (GET/PUT /sessions/{id}/tools): the wire types of the
// server's ToolList DTO (server/src/api/tools_dto.rs) and the two calls the tool screens use.

import { request } from "../api/client";

/** A magazine place a tool sits in. */
export interface PlaceRef {
  magazine: number;
  place: number;
}

/** One cutting edge D ($TC_DPn, $TC_MOPn). */
export interface ToolEdge {
  d: number;
  /** $TC_DP1 tool type (120 end mill, 200 twist drill, 5xx turning tools, ...). */
  type: number;
  position: number;
  lengths: [number, number, number];
  radius: number;
  wear_lengths: [number, number, number];
  wear_radius: number;
  more: Record<string, number>;
  /** Non-zero monitoring data by n: 1/2 time prewarning/remaining (min), 3/4 count. */
  monitoring: Record<string, number>;
}

/** One tool ($TC_TPn). */
export interface ToolEntry {
  number: number;
  name: string;
  duplo: number;
  /** $TC_TP8 bits: 1 active, 2 enabled, 4 disabled, 8 measured, 16 prewarning. */
  state: number;
  /** $TC_TP9: 0 none, 1 time, 2 count. */
  monitoring: number;
  place?: PlaceRef | null;
  auto_placed: boolean;
  in_spindle: boolean;
  edges: ToolEdge[];
}

export interface MagazinePlace {
  number: number;
  /** $TC_MPP1: 1 magazine place, 2 spindle, 3 gripper, ... */
  kind: number;
  state: number;
  tool?: number | null;
}

export interface Magazine {
  number: number;
  /** $TC_MAP1: 1 chain, 3 turret, 5 box, 7 buffer, 9 loading. */
  kind: number;
  name: string;
  places: MagazinePlace[];
}

export interface ToolList {
  spindle: number;
  prepared: number;
  tools: ToolEntry[];
  magazines: Magazine[];
}

const path = (id: string) => `/sessions/${encodeURIComponent(id)}/tools`;

export const toolsApi = {
  get: (id: string) => request<ToolList>("GET", path(id)),
  put: (id: string, list: ToolList) => request<ToolList>("PUT", path(id), list),
};
