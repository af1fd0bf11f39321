//! What the load client and the failover test share: how they reach a server.

use std::time::Duration;

/// The REST base (`…/api/v1`) and the WebSocket base of the server at `url`.
pub fn endpoints(url: &str) -> (String, String) {
    let api = format!("{}/api/v1", url.trim_end_matches('/'));
    let ws_base = api.replacen("http", "ws", 1);
    (api, ws_base)
}

/// An HTTP client that keeps enough idle connections for `concurrency` requests in flight.
pub fn http_client(concurrency: usize) -> Result<reqwest::Client, String> {
    reqwest::Client::builder()
        .pool_max_idle_per_host(concurrency.max(64))
        .timeout(Duration::from_secs(60))
        .build()
        .map_err(|e| e.to_string())
}
