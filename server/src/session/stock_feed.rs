//! The stock's changes pushed on the stream: the actor notes each new stock version as it
//! publishes the state, with the tiles cut since the version before and the meshes of the first
//! few of them; every stream client of the session sends the same encoded messages, so the HMI
//! updates its 3D stock without polling REST.
//!
//! Bounded per frame: at most [`MAX_MESHES`] tile meshes and [`MAX_MESH_BYTES`] of STL ride
//! along in one message (the others are named, the HMI fetches them over REST); the feed keeps
//! the last [`KEEP`] messages. A client whose version is not where a kept message starts (it
//! joined later, the stock was redefined, it fell behind) gets a `reload` message and fetches
//! `GET .../stock/changes?since=` itself. Meshes are only made while someone listens.

use std::collections::VecDeque;
use std::sync::Mutex;

use axum::extract::ws::{Message, Utf8Bytes};
use nctwin_engine::Channel;

use crate::api::stock_tiles::{PenTool, StockTilesMessage, TileMesh};
use crate::api::stream_frame::encode;
use crate::dto::StreamMessage;

/// Most tile meshes in one message.
pub const MAX_MESHES: usize = 4;

/// Most STL bytes of the meshes in one message (a 64 × 64 tile of a pocket is 20..200 kB).
pub const MAX_MESH_BYTES: usize = 512 * 1024;

/// Messages kept for clients a frame or two behind.
pub const KEEP: usize = 8;

/// One step of the stock's versions.
#[derive(Debug)]
struct Step {
    since: u32,
    version: u32,
    message: Utf8Bytes,
}

/// The stock messages of one session, shared by its actor and its streams.
#[derive(Debug, Default)]
pub struct StockFeed {
    /// Held for one update or one look-up, never across an await.
    inner: Mutex<Inner>,
}

#[derive(Debug, Default)]
struct Inner {
    /// The version of the newest step; `None` without a blank.
    version: Option<u32>,
    steps: VecDeque<Step>,
}

impl StockFeed {
    /// Notes the channel's stock after a step of the actor (`listening`: a stream client is
    /// subscribed; without one only the version is kept).
    pub fn update(&self, channel: &Channel, listening: bool) {
        let now = channel.stock_version();
        let mut inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        if now == inner.version {
            return;
        }
        let before = inner.version.take();
        inner.version = now;
        let Some(version) = now.filter(|_| listening) else {
            inner.steps.clear();
            return;
        };
        // A new blank starts again at version 1: everything is new.
        let since = before.filter(|b| *b < version).unwrap_or(0);
        let Some(changes) = channel.stock_delta(since) else { return };
        let mut meshes = Vec::new();
        let mut bytes = 0usize;
        for &[i, j] in changes.tiles.iter().take(MAX_MESHES) {
            let Some(stl) = channel.stock_tile_mesh(i as usize, j as usize) else { continue };
            if bytes + stl.len() > MAX_MESH_BYTES {
                break;
            }
            bytes += stl.len();
            meshes.push(TileMesh { i, j, stl: nctwin_engine::stock::saved::base64(&stl) });
        }
        let message = StockTilesMessage {
            version,
            since,
            reload: false,
            tile_cells: changes.tile,
            tiles: changes.tiles,
            pens: PenTool::list(&changes.pens),
            meshes,
        };
        if inner.steps.len() == KEEP {
            inner.steps.pop_front();
        }
        inner.steps.push_back(Step { since, version, message: encode(&StreamMessage::Stock(message)) });
    }

    /// The messages that bring a client showing version `shown` to the stock's version `now`
    /// (the state it is sent), into `out`; the version the client then shows. A client the kept
    /// steps cannot bring there gets a `reload`.
    pub fn catch_up(&self, shown: Option<u32>, now: Option<u32>, out: &mut Vec<Message>) -> Option<u32> {
        let now = now?;
        if shown == Some(now) {
            return shown;
        }
        let inner = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        let mut at = shown.unwrap_or(0);
        let start = out.len();
        while at != now {
            let Some(step) = inner.steps.iter().find(|s| s.since == at && s.version <= now) else { break };
            out.push(Message::Text(step.message.clone()));
            at = step.version;
        }
        if at != now {
            out.truncate(start);
            out.push(Message::Text(encode(&StreamMessage::Stock(StockTilesMessage::reload(now)))));
        }
        Some(now)
    }
}
