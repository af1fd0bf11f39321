//! Clients that misbehave on purpose, over real sockets: a ping flood that never reads, a
//! dead-man JOG client whose socket stalls, an oversized frame, request heads that never end,
//! more connections than one address may hold, and a stream client that stops answering pings.
//! Each must end in bounded time with the server unharmed.

use crate::common;

use std::net::SocketAddr;
use std::time::Duration;

use common::{Server, pos};
use futures_util::{SinkExt, StreamExt};
use nctwin_server::Limits;
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpSocket, TcpStream};
use tokio::time::{Instant, timeout};
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::tungstenite::protocol::frame::coding::CloseCode;
use tokio_tungstenite::{WebSocketStream, client_async};

type RawSocket = WebSocketStream<TcpStream>;

/// Guards every wait so a misbehaving server fails the test instead of hanging it.
const GUARD: Duration = Duration::from_secs(20);

/// A WebSocket client on a socket with a small receive buffer, so that a client that does not
/// read makes the server's writes block soon.
async fn small_buffer_client(server: &Server, path: &str) -> RawSocket {
    let socket = TcpSocket::new_v4().expect("socket");
    socket.set_recv_buffer_size(4096).expect("SO_RCVBUF");
    let tcp = socket.connect(server.addr).await.expect("connect");
    let (ws, _) = client_async(server.ws_url(path), tcp).await.expect("WebSocket handshake");
    ws
}

/// The header of a masked client frame with payload length `len` and the mask key 0.
fn frame_header(opcode: u8, fin: bool, len: u64) -> Vec<u8> {
    let mut out = vec![if fin { 0x80 } else { 0 } | opcode];
    match len {
        0..=125 => out.push(0x80 | len as u8),
        126..=0xFFFF => {
            out.push(0x80 | 126);
            out.extend_from_slice(&(len as u16).to_be_bytes());
        }
        _ => {
            out.push(0x80 | 127);
            out.extend_from_slice(&len.to_be_bytes());
        }
    }
    // A zero mask key leaves the payload as it is.
    out.extend_from_slice(&[0, 0, 0, 0]);
    out
}

/// A whole masked client frame.
fn frame(opcode: u8, fin: bool, payload: &[u8]) -> Vec<u8> {
    let mut out = frame_header(opcode, fin, payload.len() as u64);
    out.extend_from_slice(payload);
    out
}

/// Reads messages until the server's close frame; its code, or `None` when the connection
/// ended without one.
async fn close_code(socket: &mut RawSocket) -> Option<CloseCode> {
    loop {
        match timeout(GUARD, socket.next()).await.expect("the server closes the stream in time") {
            Some(Ok(Message::Close(frame))) => return frame.map(|f| f.code),
            Some(Ok(_)) => {}
            None | Some(Err(_)) => return None,
        }
    }
}

#[tokio::test]
async fn a_client_that_floods_pings_and_never_reads_is_disconnected() {
    let limits = Limits { stream_ping_interval: Duration::from_millis(200), ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let mut socket = small_buffer_client(&server, &format!("/sessions/{id}/stream")).await;
    // Pings of 125 bytes, written straight to the socket; nothing is ever read. Each one makes
    // the server queue a pong of as many bytes.
    let chunk: Vec<u8> = (0..500).flat_map(|_| frame(0x9, true, &[b'p'; 125])).collect();
    let started = Instant::now();
    let mut sent = 0usize;
    let closed = loop {
        assert!(
            started.elapsed() < Duration::from_secs(10),
            "still connected after {} MB of pings: the server keeps queueing pongs",
            sent >> 20
        );
        match timeout(Duration::from_secs(1), socket.get_mut().write_all(&chunk)).await {
            Ok(Ok(())) => sent += chunk.len(),
            Ok(Err(e)) => break e,
            // The server stopped reading: as good as closed if it closes soon.
            Err(_) => {}
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    };
    assert!(matches!(closed.kind(), std::io::ErrorKind::ConnectionReset | std::io::ErrorKind::BrokenPipe), "{closed}");
    // The server is unharmed and counts the stream as gone.
    let viewers = server.get(&format!("/sessions/{id}/viewers")).await;
    assert_eq!(viewers.status, StatusCode::OK);
    let mut left = viewers.body["streams"].as_u64();
    for _ in 0..100 {
        if left == Some(0) {
            break;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
        left = server.get(&format!("/sessions/{id}/viewers")).await.body["streams"].as_u64();
    }
    assert_eq!(left, Some(0));
}

#[tokio::test]
async fn a_stalled_dead_man_client_cannot_keep_a_jog_moving() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let mut socket = small_buffer_client(&server, &format!("/sessions/{id}/stream")).await;
    socket
        .send(Message::Text(json!({"type": "jog", "axis": "X", "direction": 1}).to_string().into()))
        .await
        .expect("sent");
    server.state_until(&id, "the JOG moves", |s| pos(s, "machine", "X") > 0.0).await;
    // Keep-alives, each followed by messages that are answered with an error, never reading the
    // answers, until the socket takes no more: the server's replies have nowhere to go.
    let keepalive = Message::Text(json!({"type": "jog_keepalive"}).to_string().into());
    let junk = Message::Text("x".repeat(2000).into());
    let started = Instant::now();
    loop {
        assert!(started.elapsed() < GUARD, "the socket never blocked");
        let batch = async {
            socket.feed(keepalive.clone()).await?;
            for _ in 0..20 {
                socket.feed(junk.clone()).await?;
            }
            socket.flush().await
        };
        match timeout(Duration::from_millis(300), batch).await {
            Ok(result) => result.expect("the server keeps the socket open"),
            Err(_) => break,
        }
    }
    // Silent now, with the socket open. The dead man (400 ms) must stop the axis all the same.
    let silent = Instant::now();
    let stopped = loop {
        let state = server.get(&format!("/sessions/{id}/state")).await.body;
        if state["status"] == "idle" {
            break state;
        }
        assert!(
            silent.elapsed() < Duration::from_secs(2),
            "the JOG still moves {:?} after the last keep-alive: {state}",
            silent.elapsed()
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    };
    let x = pos(&stopped, "machine", "X");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let later = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(pos(&later, "machine", "X"), x, "the axis stands: {later}");
    drop(socket);
}

#[tokio::test]
async fn an_oversized_frame_is_refused_when_its_header_arrives() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let path = format!("/sessions/{id}/stream");
    // The header of a 1 MiB text frame, and none of its payload.
    let mut socket = small_buffer_client(&server, &path).await;
    socket.get_mut().write_all(&frame_header(0x1, true, 1 << 20)).await.expect("header sent");
    assert_eq!(close_code(&mut socket).await, Some(CloseCode::Size), "closed at once with 1009");

    // A message of small frames that together exceed the limit is refused as well.
    let mut socket = small_buffer_client(&server, &path).await;
    let part = vec![b' '; 3000];
    let mut bytes = frame(0x1, false, &part);
    bytes.extend(frame(0x0, false, &part));
    socket.get_mut().write_all(&bytes).await.expect("frames sent");
    assert_eq!(close_code(&mut socket).await, Some(CloseCode::Size));

    // A message of the protocol's size still works.
    let mut socket = small_buffer_client(&server, &path).await;
    socket.send(Message::Text(json!({"type": "jog_stop"}).to_string().into())).await.expect("sent");
    loop {
        let message = timeout(GUARD, socket.next()).await.expect("an answer").expect("open").expect("a message");
        if let Message::Text(text) = message {
            let value: Value = serde_json::from_str(&text).expect("JSON");
            if value["type"] == "ack" {
                break;
            }
        }
    }
}

/// Reads until the server closes the connection; what it sent.
async fn read_to_close(tcp: &mut TcpStream, limit: Duration) -> Vec<u8> {
    let mut out = Vec::new();
    let mut buf = [0u8; 4096];
    loop {
        match timeout(limit, tcp.read(&mut buf)).await.expect("the server closes the connection in time") {
            Ok(0) | Err(_) => return out,
            Ok(n) => out.extend_from_slice(&buf[..n]),
        }
    }
}

async fn connect(addr: SocketAddr) -> TcpStream {
    TcpStream::connect(addr).await.expect("connect")
}

/// `GET /api/v1/health` with the `Host` the server answers to (its own address and port).
fn health_request(tcp: &TcpStream) -> Vec<u8> {
    let server = tcp.peer_addr().expect("connected");
    format!("GET /api/v1/health HTTP/1.1\r\nhost: {server}\r\n\r\n").into_bytes()
}

/// Sends a health request on a kept-alive connection and reads its answer's head.
async fn health_head(tcp: &mut TcpStream) -> String {
    tcp.write_all(&health_request(tcp)).await.expect("request sent");
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        let n = timeout(GUARD, tcp.read(&mut byte)).await.expect("an answer").expect("read");
        assert_eq!(n, 1, "closed before the answer: {}", String::from_utf8_lossy(&head));
        head.push(byte[0]);
    }
    String::from_utf8_lossy(&head).into_owned()
}

#[tokio::test]
async fn connections_that_never_finish_a_request_head_are_closed_after_the_timeout() {
    let limits = Limits { header_read_timeout: Duration::from_millis(300), ..Limits::default() };
    let server = Server::start_with(limits).await;
    // Half a request line.
    let mut half = connect(server.addr).await;
    half.write_all(b"GET /api/v1/hea").await.expect("sent");
    // Headers that never end.
    let mut headers = connect(server.addr).await;
    headers.write_all(b"GET /api/v1/health HTTP/1.1\r\nhost: localhost\r\nx-slow: 1\r\n").await.expect("sent");
    // Nothing at all.
    let mut silent = connect(server.addr).await;
    // A kept-alive connection after one answered request.
    let mut idle = connect(server.addr).await;
    assert!(health_head(&mut idle).await.starts_with("HTTP/1.1 200"));
    for tcp in [&mut half, &mut headers, &mut silent, &mut idle] {
        read_to_close(tcp, Duration::from_secs(5)).await;
    }
    // The server still answers.
    assert_eq!(server.get("/health").await.status, StatusCode::OK);
}

#[tokio::test]
async fn a_connection_over_the_per_ip_cap_is_answered_429_and_closed() {
    let limits = Limits { connections_per_ip: 3, ..Limits::default() };
    let server = Server::start_with(limits).await;
    // The session is made on a connection that closes (the harness' client would keep one).
    let mut make = connect(server.addr).await;
    let body = json!({"machine": "mill-3axis"}).to_string();
    let request = format!(
        "POST /api/v1/sessions HTTP/1.1\r\nhost: {}\r\ncontent-type: application/json\r\ncontent-length: {}\r\nconnection: close\r\n\r\n{body}",
        server.addr,
        body.len()
    );
    make.write_all(request.as_bytes()).await.expect("sent");
    let created = String::from_utf8(read_to_close(&mut make, GUARD).await).expect("UTF-8");
    let (_, json) = created.split_once("\r\n\r\n").expect("a head and a body");
    let id = serde_json::from_str::<Value>(json).expect("JSON")["id"].as_str().expect("id").to_string();
    drop(make);
    // Two kept-alive connections and one stream: three open connections from 127.0.0.1.
    let mut first = connect(server.addr).await;
    assert!(health_head(&mut first).await.starts_with("HTTP/1.1 200"));
    let mut second = connect(server.addr).await;
    assert!(health_head(&mut second).await.starts_with("HTTP/1.1 200"));
    let (mut stream, _) = tokio_tungstenite::connect_async(server.ws_url(&format!("/sessions/{id}/stream")))
        .await
        .expect("WebSocket handshake");
    timeout(GUARD, stream.next()).await.expect("the first state").expect("open").expect("a message");

    let mut extra = connect(server.addr).await;
    extra.write_all(&health_request(&extra)).await.expect("sent");
    let answer = String::from_utf8_lossy(&read_to_close(&mut extra, GUARD).await).into_owned();
    assert!(answer.starts_with("HTTP/1.1 429"), "{answer}");
    assert!(answer.to_ascii_lowercase().contains("connection: close"), "{answer}");
    assert!(answer.contains("\"error\""), "{answer}");

    // A closed stream frees its place.
    drop(stream);
    let started = Instant::now();
    loop {
        let mut next = connect(server.addr).await;
        next.write_all(&health_request(&next)).await.expect("sent");
        let answer = String::from_utf8_lossy(&read_to_close_or_head(&mut next).await).into_owned();
        if answer.starts_with("HTTP/1.1 200") {
            break;
        }
        assert!(started.elapsed() < Duration::from_secs(5), "the closed stream still counts: {answer}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    drop((first, second));
}

/// The answer's head of a kept-alive connection, or everything up to the close.
async fn read_to_close_or_head(tcp: &mut TcpStream) -> Vec<u8> {
    let mut out = Vec::new();
    let mut buf = [0u8; 1024];
    while !out.windows(4).any(|w| w == b"\r\n\r\n") {
        match timeout(GUARD, tcp.read(&mut buf)).await.expect("an answer") {
            Ok(0) | Err(_) => break,
            Ok(n) => out.extend_from_slice(&buf[..n]),
        }
    }
    out
}

#[tokio::test]
async fn an_idle_stream_gets_pings_and_is_closed_when_the_pongs_stop() {
    let limits = Limits { stream_ping_interval: Duration::from_millis(200), ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let mut socket = small_buffer_client(&server, &format!("/sessions/{id}/stream")).await;
    // Reading answers every ping with a pong (tungstenite does it): the stream stays open.
    let mut pings = 0;
    let reading = Instant::now();
    while reading.elapsed() < Duration::from_millis(1500) {
        match timeout(Duration::from_millis(100), socket.next()).await {
            Err(_) => {}
            Ok(Some(Ok(Message::Ping(_)))) => pings += 1,
            Ok(Some(Ok(Message::Close(frame)))) => panic!("closed while answering pings: {frame:?}"),
            Ok(Some(Ok(_))) => {}
            Ok(other) => panic!("the stream broke: {other:?}"),
        }
    }
    assert!(pings >= 4, "{pings} pings in 1.5 s at a 200 ms interval");
    // Not reading: no pongs. Two missed pings later the server closes the stream (with 1008;
    // the close frame itself may be lost here: this client answers the pings it reads late
    // with pongs to a socket the server closed, and the reset drops what was still unread).
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let code = close_code(&mut socket).await;
    assert!(matches!(code, None | Some(CloseCode::Policy)), "{code:?}");
    let metrics = server.client.get(format!("http://{}/metrics", server.addr)).send().await.expect("metrics");
    let metrics = metrics.text().await.expect("metrics text");
    assert!(metrics.contains("nctwin_stream_closes_total{reason=\"pongs_missed\"} 1\n"), "{metrics}");
}
