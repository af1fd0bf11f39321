//! Cross-site requests: a web page of another site that the user visits cannot drive the local
//! server (CSRF with simple requests, DNS rebinding, cross-site WebSockets), while the HMI (same
//! origin), `curl` and the operator's listed origins and names keep working.

use crate::common;

use std::net::SocketAddr;

use common::{Server, error_message};
use nctwin_server::{AppState, Config};
use reqwest::StatusCode;
use serde_json::json;
use tokio::net::TcpListener;
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Error as WsError;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;

const EVIL: &str = "http://evil.example";

fn config(allow_origins: &[&str], allow_hosts: &[&str]) -> Config {
    Config {
        allow_origins: allow_origins.iter().map(|s| s.to_string()).collect(),
        allow_hosts: allow_hosts.iter().map(|s| s.to_string()).collect(),
        ..Config::new(common::temp_data_dir(), common::WEB_DIR)
    }
}

#[tokio::test]
async fn a_json_body_needs_a_json_content_type() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let run = r#"{"program": "G1 X10 F1000\nM30", "pace": "fast", "wait": true}"#;
    // What an HTML form or a `no-cors` fetch of another site can send without a preflight.
    for content_type in
        [Some("text/plain"), Some("application/x-www-form-urlencoded"), Some("multipart/form-data"), None]
    {
        let mut request = server.client.post(server.url(&format!("/sessions/{id}/run"))).body(run);
        if let Some(content_type) = content_type {
            request = request.header("content-type", content_type);
        }
        let reply = server.send(request).await;
        let message = error_message(&reply, StatusCode::UNSUPPORTED_MEDIA_TYPE);
        assert!(message.contains("application/json"), "{content_type:?}: {message}");
    }
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["status"], "idle", "nothing ran: {state}");
    assert_eq!(state["positions"]["machine"]["X"], 0.0);

    // JSON with parameters, and requests without a body, keep working.
    let request = server
        .client
        .post(server.url(&format!("/sessions/{id}/run")))
        .header("content-type", "application/json; charset=utf-8")
        .body(run);
    assert_eq!(server.send(request).await.status, StatusCode::OK);
    assert_eq!(server.post_empty(&format!("/sessions/{id}/reset")).await.status, StatusCode::OK);
    assert_eq!(server.post_empty(&format!("/sessions/{id}/start")).await.status, StatusCode::OK);
    assert_eq!(server.post_empty("/sessions").await.status, StatusCode::CREATED);
    // An empty body with a form content type is no body (curl -X POST -d '').
    let request =
        server.client.post(server.url("/sessions")).header("content-type", "application/x-www-form-urlencoded");
    assert_eq!(server.send(request).await.status, StatusCode::CREATED);
    // The one text endpoint takes text.
    let chains =
        server.client.put(server.url(&format!("/sessions/{id}/kinematic-chains"))).header("content-type", "text/plain");
    assert_ne!(server.send(chains.body("")).await.status, StatusCode::UNSUPPORTED_MEDIA_TYPE);
}

#[tokio::test]
async fn requests_from_another_origin_are_refused() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let sessions_before = server.get("/sessions").await.body.as_array().map(Vec::len);
    for origin in [EVIL, "null", "http://localhost:1", "https://127.0.0.1.evil.example"] {
        let create = server.client.post(server.url("/sessions")).header("origin", origin);
        let message = error_message(&server.send(create).await, StatusCode::FORBIDDEN);
        assert!(message.contains(origin) && message.contains("--allow-origin"), "{message}");
        // A body-less POST is a "simple" request a page can send anywhere without a preflight.
        let reset = server.client.post(server.url(&format!("/sessions/{id}/reset"))).header("origin", origin);
        error_message(&server.send(reset).await, StatusCode::FORBIDDEN);
        let read = server.client.get(server.url("/machines")).header("origin", origin);
        error_message(&server.send(read).await, StatusCode::FORBIDDEN);
    }
    assert_eq!(server.get("/sessions").await.body.as_array().map(Vec::len), sessions_before, "nothing was created");

    // A preflight from another origin gets no CORS permission.
    let preflight = server
        .client
        .request(reqwest::Method::OPTIONS, server.url("/sessions"))
        .header("origin", EVIL)
        .header("access-control-request-method", "POST")
        .header("access-control-request-headers", "content-type");
    let reply = server.send(preflight).await;
    assert!(reply.headers.get("access-control-allow-origin").is_none(), "{:?}", reply.headers);
    assert!(!reply.status.is_success(), "{}", reply.status);
}

#[tokio::test]
async fn the_servers_own_origin_and_clients_without_an_origin_are_served() {
    let server = Server::start().await;
    let port = server.addr.port();
    // The HMI and Swagger UI: the page's origin is the server's own.
    for (host, origin) in [
        (format!("127.0.0.1:{port}"), format!("http://127.0.0.1:{port}")),
        (format!("localhost:{port}"), format!("http://localhost:{port}")),
        (format!("LocalHost:{port}"), format!("http://localhost:{port}")),
    ] {
        let create = server.client.post(server.url("/sessions")).header("host", &host).header("origin", &origin);
        let reply = server.send(create).await;
        assert_eq!(reply.status, StatusCode::CREATED, "{host} {origin}: {}", reply.body);
    }
    // curl, scripts and the test harness send no Origin.
    assert_eq!(server.post_empty("/sessions").await.status, StatusCode::CREATED);
}

#[tokio::test]
async fn listed_origins_may_call_the_api_across_sites() {
    let hmi = "http://hmi.example:3000";
    let server = Server::start_config(config(&[hmi], &[])).await;
    let preflight = server
        .client
        .request(reqwest::Method::OPTIONS, server.url("/sessions"))
        .header("origin", hmi)
        .header("access-control-request-method", "POST")
        .header("access-control-request-headers", "content-type");
    let reply = server.send(preflight).await;
    assert!(reply.status.is_success(), "{}", reply.status);
    assert_eq!(reply.headers["access-control-allow-origin"], hmi);
    let create = server.client.post(server.url("/sessions")).header("origin", hmi).json(&json!({}));
    let reply = server.send(create).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    assert_eq!(reply.headers["access-control-allow-origin"], hmi);
    let other = server.client.post(server.url("/sessions")).header("origin", "http://hmi.example:3001");
    error_message(&server.send(other).await, StatusCode::FORBIDDEN);
}

#[tokio::test]
async fn a_websocket_from_another_origin_is_refused() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let url = server.ws_url(&format!("/sessions/{id}/stream"));
    let mut request = url.as_str().into_client_request().expect("request");
    request.headers_mut().insert("origin", EVIL.parse().expect("header"));
    match connect_async(request).await {
        Err(WsError::Http(response)) => assert_eq!(response.status(), StatusCode::FORBIDDEN),
        other => panic!("expected 403, got {:?}", other.map(|(_, r)| r.status())),
    }
    let mut request = url.as_str().into_client_request().expect("request");
    let own = format!("http://{}", server.addr);
    request.headers_mut().insert("origin", own.parse().expect("header"));
    connect_async(request).await.expect("the HMI's own origin connects");
    connect_async(url.as_str()).await.expect("a client without an origin connects");
}

#[tokio::test]
async fn a_host_that_is_not_the_servers_is_refused() {
    let server = Server::start().await;
    let port = server.addr.port();
    // DNS rebinding: a page of evil.example whose name now resolves to 127.0.0.1.
    for host in [
        format!("evil.example:{port}"),
        "evil.example".to_string(),
        format!("localhost:{}", port.wrapping_add(1)),
        "localhost".to_string(),
        format!("127.0.0.2:{port}"),
        format!("localhost.evil.example:{port}"),
    ] {
        for path in ["/api/v1/machines", "/", "/metrics", "/api/v1/openapi.json"] {
            let url = format!("http://{}{path}", server.addr);
            let reply = server.send(server.client.get(url).header("host", &host)).await;
            let message = error_message(&reply, StatusCode::FORBIDDEN);
            assert!(message.contains(&host) && message.contains("--allow-host"), "{host}{path}: {message}");
        }
        let mut request = server.ws_url("/sessions/x/stream").into_client_request().expect("request");
        request.headers_mut().insert("host", host.parse().expect("header"));
        match connect_async(request).await {
            Err(WsError::Http(response)) => assert_eq!(response.status(), StatusCode::FORBIDDEN),
            other => panic!("expected 403, got {:?}", other.map(|(_, r)| r.status())),
        }
    }
    for host in [format!("localhost:{port}"), format!("127.0.0.1:{port}"), format!("[::1]:{port}")] {
        let url = format!("http://{}/api/v1/machines", server.addr);
        assert_eq!(server.send(server.client.get(url).header("host", &host)).await.status, StatusCode::OK, "{host}");
    }
}

#[tokio::test]
async fn names_the_operator_lists_are_served() {
    let server = Server::start_config(config(&[], &["nctwin.lan", "cell-7:8443"])).await;
    let port = server.addr.port();
    let machines = format!("http://{}/api/v1/machines", server.addr);
    for host in [format!("nctwin.lan:{port}"), "NCTWIN.lan".to_string(), "cell-7:8443".to_string()] {
        assert_eq!(
            server.send(server.client.get(&machines).header("host", &host)).await.status,
            StatusCode::OK,
            "{host}"
        );
    }
    for host in [format!("cell-7:{port}"), format!("other.lan:{port}")] {
        error_message(&server.send(server.client.get(&machines).header("host", &host)).await, StatusCode::FORBIDDEN);
    }
    // A page served under a listed name is the server's own origin.
    let create = server
        .client
        .post(server.url("/sessions"))
        .header("host", format!("nctwin.lan:{port}"))
        .header("origin", format!("http://nctwin.lan:{port}"));
    assert_eq!(server.send(create).await.status, StatusCode::CREATED);
}

#[tokio::test]
async fn a_server_bound_to_every_interface_answers_its_addresses_and_listed_names() {
    let listener = TcpListener::bind("0.0.0.0:0").await.expect("bind 0.0.0.0:0");
    let port = listener.local_addr().expect("address").port();
    let config = config(&[], &["nctwin.lan"]);
    let data_dir = config.data_dir.clone();
    let state = AppState::open(config).await.expect("storage opens");
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let task = tokio::spawn(nctwin_server::run(listener, state, async {
        let _ = stopped.await;
    }));
    let addr = SocketAddr::from(([127, 0, 0, 1], port));
    let client = reqwest::Client::new();
    let get = |host: String| client.get(format!("http://{addr}/api/v1/health")).header("host", host).send();
    // The addresses LAN clients use: an address literal cannot be a rebound name.
    for host in [format!("192.168.77.5:{port}"), format!("[fd00::5]:{port}"), format!("localhost:{port}")] {
        assert_eq!(get(host.clone()).await.expect("reply").status(), StatusCode::OK, "{host}");
    }
    assert_eq!(get(format!("nctwin.lan:{port}")).await.expect("reply").status(), StatusCode::OK);
    for host in [format!("192.168.77.5:{}", port.wrapping_add(1)), format!("pc.lan:{port}")] {
        assert_eq!(get(host.clone()).await.expect("reply").status(), StatusCode::FORBIDDEN, "{host}");
    }
    let _ = stop.send(());
    task.await.expect("server task").expect("server ran");
    let _ = std::fs::remove_dir_all(data_dir);
}
