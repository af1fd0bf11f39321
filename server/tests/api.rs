//! The REST API over real HTTP on port 0: every endpoint, the behaviour of programs, and bad
//! input of every kind.

use crate::common;

use std::time::Duration;

use common::{Server, error_message, pos};
use nctwin_server::Limits;
use reqwest::StatusCode;
use serde_json::{Value, json};

// ---- health and machines ----

#[tokio::test]
async fn health_reports_ok_version_session_count_and_storage() {
    let server = Server::start().await;
    let reply = server.get("/health").await;
    assert_eq!(reply.status, StatusCode::OK);
    assert_eq!(
        (&reply.body["status"], &reply.body["version"], &reply.body["sessions"]),
        (&json!("ok"), &json!("0.1.0"), &json!(0))
    );
    assert_eq!(reply.body["storage"], json!({"backend": "sqlite", "status": "ok"}));
    assert_eq!(reply.body["auth"], "off");
    server.session("mill-3axis").await;
    assert_eq!(server.get("/health").await.body["sessions"], 1);
}

#[tokio::test]
async fn machines_lists_the_presets_including_the_3_axis_mill() {
    let server = Server::start().await;
    let reply = server.get("/machines").await;
    assert_eq!(reply.status, StatusCode::OK);
    let list = reply.body.as_array().expect("array");
    let mill = list.iter().find(|m| m["id"] == "mill-3axis").expect("mill-3axis listed");
    assert!(mill["name"].is_string() && mill["description"].is_string());
    assert_eq!(mill.as_object().map(|o| o.len()), Some(3), "{mill}");
    // Every engine preset is offered, the 6-axis head among them.
    assert_eq!(list.len(), nctwin_engine::machine_data::presets::PRESETS.len());
    assert!(list.iter().any(|m| m["id"] == "mill6-generic"), "{list:?}");
}

#[tokio::test]
async fn a_machine_comes_with_its_machine_data_text_and_unknown_ones_are_404() {
    let server = Server::start().await;
    let reply = server.get("/machines/mill-3axis").await;
    assert_eq!(reply.status, StatusCode::OK);
    assert_eq!(reply.body["id"], "mill-3axis");
    assert!(reply.body["machine_data"].as_str().expect("text").contains("$MN_AXCONF_MACHAX_NAME_TAB"));
    let message = error_message(&server.get("/machines/no-such-machine").await, StatusCode::NOT_FOUND);
    assert!(message.contains("no-such-machine"), "{message}");
}

// ---- sessions ----

#[tokio::test]
async fn a_session_is_created_with_defaults_from_an_empty_body() {
    let server = Server::start().await;
    let reply = server.post_empty("/sessions").await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    assert_eq!(reply.body["machine"], "mill-3axis");
    let id = reply.body["id"].as_str().expect("id");
    assert_eq!(reply.headers["location"], format!("/api/v1/sessions/{id}").as_str());
    let state = &reply.body["state"];
    assert_eq!(state["status"], "idle");
    assert_eq!(state["mode"], "AUTO");
    assert_eq!(state["time"], 0.0);
    let machine: Vec<&String> = state["positions"]["machine"].as_object().expect("object").keys().collect();
    assert_eq!(machine, ["X", "Y", "Z"]);
    assert!(state["transformation"].is_null() && state["block"].is_null());
    assert_eq!(state["alarms"], json!([]));
}

#[tokio::test]
async fn a_session_takes_a_preset_and_extra_machine_data() {
    let server = Server::start().await;
    let body = json!({"machine": "lathe-2axis", "machine_data": "; softer limit\n$MA_POS_LIMIT_PLUS[Z1]=350."});
    let reply = server.post("/sessions", body).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    assert_eq!(reply.body["machine"], "lathe-2axis");
    assert!(reply.body["state"]["positions"]["machine"].get("Z1").is_some(), "{}", reply.body);
}

#[tokio::test]
async fn unknown_presets_and_bad_machine_data_are_400_naming_the_problem() {
    let server = Server::start().await;
    let message =
        error_message(&server.post("/sessions", json!({"machine": "hexapod"})).await, StatusCode::BAD_REQUEST);
    assert!(message.contains("hexapod"), "{message}");

    let reply = server.post("/sessions", json!({"machine_data": "; first line\n$MA_NO_SUCH_DATUM[X]=1"})).await;
    let message = error_message(&reply, StatusCode::BAD_REQUEST);
    assert_eq!(reply.body["line"], 2, "{}", reply.body);
    assert!(message.contains("$MA_NO_SUCH_DATUM"), "{message}");
    assert_eq!(server.get("/health").await.body["sessions"], 0, "nothing was created");
}

#[tokio::test]
async fn sessions_are_listed_read_and_deleted() {
    let server = Server::start().await;
    let a = server.session("mill-3axis").await;
    let b = server.session("lathe-2axis").await;
    assert_ne!(a, b);

    let list = server.get("/sessions").await;
    assert_eq!(list.status, StatusCode::OK);
    assert_eq!(
        list.body,
        json!([
            {"id": a, "machine": "mill-3axis", "status": "idle", "mode": "AUTO"},
            {"id": b, "machine": "lathe-2axis", "status": "idle", "mode": "AUTO"},
        ])
    );

    let one = server.get(&format!("/sessions/{a}")).await;
    assert_eq!(one.status, StatusCode::OK);
    assert_eq!((one.body["id"].as_str(), one.body["machine"].as_str()), (Some(a.as_str()), Some("mill-3axis")));
    assert_eq!(one.body["state"]["status"], "idle");

    let deleted = server.delete(&format!("/sessions/{a}")).await;
    assert_eq!(deleted.status, StatusCode::NO_CONTENT);
    assert_eq!(deleted.body, Value::Null);
    error_message(&server.get(&format!("/sessions/{a}")).await, StatusCode::NOT_FOUND);
    error_message(&server.delete(&format!("/sessions/{a}")).await, StatusCode::NOT_FOUND);
    assert_eq!(server.get("/sessions").await.body.as_array().map(Vec::len), Some(1));
}

#[tokio::test]
async fn unknown_sessions_are_404_on_every_endpoint() {
    let server = Server::start().await;
    let id = "nosuch";
    let replies = [
        server.get(&format!("/sessions/{id}")).await,
        server.get(&format!("/sessions/{id}/state")).await,
        server.delete(&format!("/sessions/{id}")).await,
        server.post(&format!("/sessions/{id}/run"), json!({"program": "M30"})).await,
        server.post_empty(&format!("/sessions/{id}/start")).await,
        server.post_empty(&format!("/sessions/{id}/stop")).await,
        server.post_empty(&format!("/sessions/{id}/reset")).await,
        server.post_empty(&format!("/sessions/{id}/cancel")).await,
        server.post(&format!("/sessions/{id}/mda"), json!({"program": "G0 X1"})).await,
        server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await,
        server.post(&format!("/sessions/{id}/jog"), json!({"axis": "X", "direction": 1})).await,
        server.post_empty(&format!("/sessions/{id}/jog/stop")).await,
        server.put(&format!("/sessions/{id}/machine-data"), json!({"text": ""})).await,
        server.get(&format!("/sessions/{id}/stream")).await,
    ];
    for reply in replies {
        let message = error_message(&reply, StatusCode::NOT_FOUND);
        assert!(message.contains(id), "{message}");
    }
}

// ---- programs ----

#[tokio::test]
async fn a_fast_run_with_wait_answers_with_the_final_state() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X10 Y20 Z30\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let state = &reply.body;
    assert_eq!(state["status"], "idle");
    assert_eq!(pos(state, "machine", "X"), 10.0);
    assert_eq!(pos(state, "workpiece", "Y"), 20.0);
    assert_eq!(pos(state, "basic", "Z"), 30.0);
    assert!(state["time"].as_f64().expect("time") > 0.0);
    assert!(reply.headers.get("nctwin-limit").is_none());
    assert_eq!(server.get(&format!("/sessions/{id}/state")).await.body, reply.body, "state is kept");
}

#[tokio::test]
async fn m0_stops_the_program_and_start_continues_it() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "G1 X10 F1000\nM0\nG1 X20\nM30";
    let stopped =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(stopped.status, StatusCode::OK, "{}", stopped.body);
    assert_eq!(stopped.body["status"], "stopped");
    assert_eq!(stopped.body["block"]["line"], 2);
    assert_eq!(stopped.body["block"]["text"], "M0");
    assert_eq!(pos(&stopped.body, "machine", "X"), 10.0);

    let ended = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(ended.status, StatusCode::OK, "{}", ended.body);
    assert_eq!(ended.body["status"], "idle");
    assert_eq!(pos(&ended.body, "machine", "X"), 20.0);
}

#[tokio::test]
async fn m1_stops_only_with_optional_stop() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "G1 X5 F1000\nM1\nG1 X6\nM30";
    let skipped =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!((skipped.body["status"].as_str(), pos(&skipped.body, "machine", "X")), (Some("idle"), 6.0));
    let body = json!({"program": program, "pace": "fast", "wait": true, "optional_stop": true});
    let stopped = server.post(&format!("/sessions/{id}/run"), body).await;
    assert_eq!((stopped.body["status"].as_str(), pos(&stopped.body, "machine", "X")), (Some("stopped"), 5.0));
}

#[tokio::test]
async fn a_realtime_run_with_wait_ends_at_the_program_end() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // 10 mm at 6000 mm/min: about 0.1 s of simulated (and wall) time.
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X10 F6000\nM30", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "idle");
    assert_eq!(pos(&reply.body, "machine", "X"), 10.0);
}

#[tokio::test]
async fn a_run_without_wait_answers_at_once_and_the_program_runs_on() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X10 F3000\nM30"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "running");
    let end = server.state_until(&id, "program end", |s| s["status"] == "idle").await;
    assert_eq!(pos(&end, "machine", "X"), 10.0);
}

#[tokio::test]
async fn a_syntax_error_is_400_with_its_line_and_nothing_moves() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    let reply = server
        .post(
            &format!("/sessions/{id}/run"),
            json!({"program": "G1 X10 F1000\nG1 X=\nWHILE R1<2\nM30", "pace": "fast", "wait": true}),
        )
        .await;
    error_message(&reply, StatusCode::BAD_REQUEST);
    assert_eq!(reply.body["line"], 2, "{}", reply.body);
    // Every error, as the NC alarm: the missing value of line 2 (12080, column 6) and the
    // WHILE of line 3 that is never closed (12640).
    let errors: Vec<(u64, u64, u64)> = reply.body["errors"]
        .as_array()
        .expect("errors")
        .iter()
        .map(|e| (e["alarm"].as_u64().unwrap(), e["line"].as_u64().unwrap(), e["column"].as_u64().unwrap()))
        .collect();
    assert_eq!(errors, [(12080, 2, 6), (12640, 3, 1)], "{}", reply.body);
    let after = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(after["positions"], before["positions"]);
    assert_eq!(after["status"], "idle");

    let mda = server.post(&format!("/sessions/{id}/mda"), json!({"program": "G1 X="})).await;
    error_message(&mda, StatusCode::BAD_REQUEST);
    assert_eq!(mda.body["line"], 1);
}

#[tokio::test]
async fn stop_interrupts_a_program_and_start_finishes_it() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // 100 mm at 600 mm/min: ten seconds.
    let running = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30"})).await;
    assert_eq!(running.body["status"], "running");
    let stopped = server.post_empty(&format!("/sessions/{id}/stop")).await;
    assert_eq!(stopped.status, StatusCode::OK, "{}", stopped.body);
    assert_eq!(stopped.body["status"], "stopped");
    let ended = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(ended.status, StatusCode::OK, "{}", ended.body);
    assert_eq!(ended.body["status"], "idle");
    assert_eq!(pos(&ended.body, "machine", "X"), 100.0);
}

#[tokio::test]
async fn reset_ends_a_program_and_clears_alarms() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // Beyond the +500 mm software limit: alarm 10720.
    let alarm = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X600\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(alarm.status, StatusCode::OK, "{}", alarm.body);
    assert_eq!(alarm.body["status"], "alarm");
    assert_eq!(alarm.body["alarms"][0]["number"], 10720);
    assert_eq!(alarm.body["alarms"][0]["line"], 1);

    let refused = server.post(&format!("/sessions/{id}/run"), json!({"program": "G0 X1"})).await;
    error_message(&refused, StatusCode::CONFLICT);

    let reset = server.post_empty(&format!("/sessions/{id}/reset")).await;
    assert_eq!(reset.status, StatusCode::OK);
    assert_eq!(reset.body["status"], "idle");
    assert_eq!(reset.body["alarms"], json!([]));
}

#[tokio::test]
async fn mda_executes_blocks_in_mda_mode() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server
        .post(&format!("/sessions/{id}/mda"), json!({"program": "G91 G1 X5 F500", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["mode"], "MDA");
    assert_eq!(reply.body["status"], "idle");
    assert_eq!(pos(&reply.body, "machine", "X"), 5.0);
}

// ---- mode, JOG, cancel ----

#[tokio::test]
async fn jog_in_auto_mode_is_409() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{id}/jog"), json!({"axis": "X", "direction": 1})).await;
    let message = error_message(&reply, StatusCode::CONFLICT);
    assert!(message.contains("JOG"), "{message}");
}

#[tokio::test]
async fn jog_moves_an_axis_by_an_increment_or_until_released() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mode = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(mode.status, StatusCode::OK, "{}", mode.body);
    assert_eq!(mode.body["mode"], "JOG");

    let body = json!({"axis": "Y", "direction": -1, "increment": 5.0, "pace": "fast", "wait": true});
    let stepped = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(stepped.status, StatusCode::OK, "{}", stepped.body);
    assert_eq!(stepped.body["status"], "idle");
    assert_eq!(pos(&stepped.body, "machine", "Y"), -5.0);

    let moving = server.post(&format!("/sessions/{id}/jog"), json!({"axis": "X", "direction": 1})).await;
    assert_eq!(moving.status, StatusCode::OK, "{}", moving.body);
    assert_eq!(moving.body["status"], "running");
    server.state_until(&id, "X moving", |s| pos(s, "machine", "X") > 0.0).await;
    let released = server.post_empty(&format!("/sessions/{id}/jog/stop")).await;
    assert_eq!(released.status, StatusCode::OK, "{}", released.body);
    let stands = server.state_until(&id, "JOG axis at standstill", |s| s["status"] == "idle").await;
    let x = pos(&stands, "machine", "X");
    assert!(x > 0.0 && x < 500.0, "X = {x}");
    assert_eq!(stands["alarms"], json!([]));
}

#[tokio::test]
async fn bad_jog_requests_are_400() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    let unknown = server.post(&format!("/sessions/{id}/jog"), json!({"axis": "Q", "direction": 1})).await;
    assert!(error_message(&unknown, StatusCode::BAD_REQUEST).contains('Q'));
    let direction = server.post(&format!("/sessions/{id}/jog"), json!({"axis": "X", "direction": 2})).await;
    error_message(&direction, StatusCode::BAD_REQUEST);
    let increment =
        server.post(&format!("/sessions/{id}/jog"), json!({"axis": "X", "direction": 1, "increment": -3})).await;
    error_message(&increment, StatusCode::BAD_REQUEST);
}

#[tokio::test]
async fn a_jog_to_the_software_limit_raises_an_alarm_that_cancel_clears() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    let body = json!({"axis": "Z", "direction": 1, "rapid": true, "pace": "fast", "wait": true});
    let at_limit = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(at_limit.status, StatusCode::OK, "{}", at_limit.body);
    assert_eq!(pos(&at_limit.body, "machine", "Z"), 300.0);
    assert_eq!(at_limit.body["alarms"][0]["number"], 10621, "{}", at_limit.body);

    let cancelled = server.post_empty(&format!("/sessions/{id}/cancel")).await;
    assert_eq!(cancelled.status, StatusCode::OK);
    assert_eq!(cancelled.body["alarms"], json!([]));
}

#[tokio::test]
async fn the_mode_cannot_change_while_a_program_runs() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30"})).await;
    let reply = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    error_message(&reply, StatusCode::CONFLICT);
    let bad = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "MANUAL"})).await;
    error_message(&bad, StatusCode::BAD_REQUEST);
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    let reply = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
}

// ---- machine data ----

#[tokio::test]
async fn machine_data_applies_in_reset_state_and_bad_text_names_its_line() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let path = format!("/sessions/{id}/machine-data");
    let applied = server.put(&path, json!({"text": "$MA_POS_LIMIT_PLUS[X]=50."})).await;
    assert_eq!(applied.status, StatusCode::OK, "{}", applied.body);
    let alarm = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X60\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(alarm.body["alarms"][0]["number"], 10720, "the new limit is active: {}", alarm.body);
    server.post_empty(&format!("/sessions/{id}/reset")).await;

    let bad = server.put(&path, json!({"text": "$MA_POS_LIMIT_PLUS[X]=40.\n$MA_POS_LIMIT_PLUS[X]=\"far\""})).await;
    error_message(&bad, StatusCode::BAD_REQUEST);
    assert_eq!(bad.body["line"], 2);

    server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X10 F60\nM30"})).await;
    let busy = server.put(&path, json!({"text": "$MA_POS_LIMIT_PLUS[X]=40."})).await;
    error_message(&busy, StatusCode::CONFLICT);
}

// ---- limits ----

#[tokio::test]
async fn a_fast_run_stops_at_the_simulated_time_limit() {
    let limits = Limits { fast_sim_time: 1.0, ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    // 100 mm at 600 mm/min takes ten simulated seconds.
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.headers["nctwin-limit"], "fast-sim-time");
    assert_eq!(reply.body["status"], "stopped");
    let x = pos(&reply.body, "machine", "X");
    assert!(x > 0.0 && x < 100.0, "X = {x}");
}

#[tokio::test]
async fn a_wait_ends_at_the_wall_time_limit() {
    let limits = Limits { wait_wall_time: Duration::from_millis(200), ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.headers["nctwin-limit"], "wait-wall-time");
    assert_eq!(reply.body["status"], "running");
}

#[tokio::test]
async fn a_waiting_request_ends_with_404_when_its_session_is_deleted() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let request = server.client.post(server.url(&format!("/sessions/{id}/run")));
    let waiting = tokio::spawn(request.json(&json!({"program": "G1 X100 F60\nM30", "wait": true})).send());
    server.state_until(&id, "program running", |s| s["status"] == "running").await;
    assert_eq!(server.delete(&format!("/sessions/{id}")).await.status, StatusCode::NO_CONTENT);
    let response = waiting.await.expect("task").expect("response");
    assert_eq!(response.status(), StatusCode::NOT_FOUND);
}

// ---- bad input ----

#[tokio::test]
async fn malformed_json_is_400() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post_raw(&format!("/sessions/{id}/run"), "{\"program\": ").await;
    let message = error_message(&reply, StatusCode::BAD_REQUEST);
    assert!(message.contains("JSON"), "{message}");
    let reply = server.post_raw("/sessions", "not json").await;
    error_message(&reply, StatusCode::BAD_REQUEST);
}

#[tokio::test]
async fn unknown_fields_wrong_types_and_missing_fields_are_400_naming_the_field() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let run = format!("/sessions/{id}/run");
    for (body, needle) in [
        (json!({"program": "M30", "speed": 3}), "speed"),
        (json!({"program": 42}), "program"),
        (json!({"program": "M30", "wait": "yes"}), "wait"),
        (json!({"program": "M30", "pace": "slow"}), "slow"),
        (json!({"wait": true}), "program"),
    ] {
        let message = error_message(&server.post(&run, body.clone()).await, StatusCode::BAD_REQUEST);
        assert!(message.contains(needle), "{body}: {message}");
    }
    let message = error_message(&server.post("/sessions", json!({"machines": "x"})).await, StatusCode::BAD_REQUEST);
    assert!(message.contains("machines"), "{message}");
    let message = error_message(&server.post_empty(&run).await, StatusCode::BAD_REQUEST);
    assert!(message.contains("empty"), "{message}");
}

#[tokio::test]
async fn a_body_over_1_mib_is_413() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "G1 X1 F100\n".repeat(100_000);
    let reply = server.post(&format!("/sessions/{id}/run"), json!({"program": program})).await;
    error_message(&reply, StatusCode::PAYLOAD_TOO_LARGE);
    // Without a length up front (chunked), the limit holds as well.
    let chunks = futures_util::stream::iter((0..2048).map(|_| Ok::<_, std::io::Error>(vec![b' '; 1024])));
    let reply = server.post_raw("/sessions", reqwest::Body::wrap_stream(chunks)).await;
    error_message(&reply, StatusCode::PAYLOAD_TOO_LARGE);
}

#[tokio::test]
async fn unknown_routes_and_methods_answer_json() {
    let server = Server::start().await;
    error_message(&server.get("/no/such/thing").await, StatusCode::NOT_FOUND);
    error_message(&server.post_empty("/no/such/thing").await, StatusCode::NOT_FOUND);
    error_message(&server.delete("/health").await, StatusCode::METHOD_NOT_ALLOWED);
}

// ---- documents ----

#[tokio::test]
async fn the_openapi_document_and_swagger_ui_are_served() {
    let server = Server::start().await;
    let doc = server.get("/openapi.json").await;
    assert_eq!(doc.status, StatusCode::OK);
    assert!(doc.body["openapi"].as_str().expect("version").starts_with("3.1"));
    assert!(doc.body["paths"].get("/api/v1/sessions/{id}/run").is_some());
    let ui = server.client.get(format!("http://{}/api/docs/", server.addr)).send().await.expect("swagger ui");
    assert_eq!(ui.status(), StatusCode::OK);
    assert!(ui.text().await.expect("html").contains("swagger"), "Swagger UI page");
}

#[tokio::test]
async fn the_hmi_is_served_at_the_root() {
    let server = Server::start().await;
    let index = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../web/index.html"));
    let response = server.client.get(format!("http://{}/", server.addr)).send().await.expect("root");
    if index.is_file() {
        assert_eq!(response.status(), StatusCode::OK);
        assert!(response.headers()["content-type"].to_str().expect("type").starts_with("text/html"));
    } else {
        assert_eq!(response.status(), StatusCode::NOT_FOUND);
    }
}

#[tokio::test]
async fn overrides_scale_a_run_and_bad_values_are_400() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/overrides"), json!({"feed": 50})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["overrides"], json!({"feed": 50.0, "rapid": 100.0, "spindle": 100.0}));
    let state = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F3000\nM30", "pace": "fast", "wait": true}))
        .await
        .body;
    // 100 mm at 50 % of 3000 mm/min: 4 s plus the ramps (25/3000 s).
    let t = state["time"].as_f64().unwrap();
    assert!((t - 4.0 - 25.0 / 3000.0).abs() < 0.01, "{t}");
    let reply = server.put(&format!("/sessions/{id}/overrides"), json!({"feed": 130})).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST);
    assert!(reply.body["error"].as_str().unwrap().contains("feed override"));
}

#[tokio::test]
async fn single_block_stops_after_each_moving_block() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/options"), json!({"single_block": true})).await;
    assert_eq!((reply.status, reply.body["single_block"].clone()), (StatusCode::OK, json!(true)));
    let run = json!({"program": "G0 X10\nG0 Y10\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!((state["status"].clone(), state["block"]["line"].clone()), (json!("stopped"), json!(1)));
    let start = json!({"pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/start"), start.clone()).await.body;
    assert_eq!((state["status"].clone(), state["block"]["line"].clone()), (json!("stopped"), json!(2)));
    let state = server.post(&format!("/sessions/{id}/start"), start).await.body;
    assert_eq!(state["status"], "idle");
}

#[tokio::test]
async fn skip_levels_and_dry_run_are_options_published_in_the_state() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/options"), json!({"skip_levels": [2, 0], "dry_run": true})).await;
    assert_eq!(reply.status, StatusCode::OK);
    assert_eq!((reply.body["skip_levels"].clone(), reply.body["dry_run"].clone()), (json!([0, 2]), json!(true)));
    // /0 and /2 active: lines 2 and 4 are skipped, /1 on line 3 runs: X 30, Y 0.
    // DRY (SD42100 5000 mm/min, mode 0): the 30 mm of F100 take 30/83.33 + 83.33/3000 = 0.39 s
    // at the dry-run feed instead of 18 s at F100.
    let program = "G1 X10 F100\n/G1 X20\n/1 G1 X30\n/2 G1 Y5\nM30";
    let run = json!({"program": program, "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!((pos(&state, "machine", "X"), pos(&state, "machine", "Y")), (30.0, 0.0));
    let time = state["time"].as_f64().unwrap();
    assert!(time < 1.0, "DRY: {time} s");
    // The run's body sets them too: no level, DRY off.
    let run = json!({"program": "G1 X0 F6000\n/G1 Y5\nM30", "pace": "fast", "wait": true, "skip_levels": [], "dry_run": false});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!((state["skip_levels"].clone(), state["dry_run"].clone()), (json!([]), json!(false)));
    assert_eq!(pos(&state, "machine", "Y"), 5.0);
}

#[tokio::test]
async fn a_skip_level_outside_0_to_9_is_400_naming_it() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    for bad in [10, -1, 300] {
        let reply = server.put(&format!("/sessions/{id}/options"), json!({"skip_levels": [0, bad]})).await;
        let message = error_message(&reply, StatusCode::BAD_REQUEST);
        assert!(message.contains(&format!("skip level {bad}")), "{message}");
    }
    let run = json!({"program": "G0 X5\nM30", "pace": "fast", "wait": true, "skip_levels": [12]});
    let reply = server.post(&format!("/sessions/{id}/run"), run).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("skip level 12"));
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!((state["skip_levels"].clone(), pos(&state, "machine", "X")), (json!([]), 0.0));
}

#[tokio::test]
async fn a_program_that_computes_forever_is_stopped_by_the_fast_wall_time_limit() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let run = json!({"program": "LOOP\nR1=R1+1\nENDLOOP", "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/run"), run).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "stopped");
    assert!(reply.headers.get("nctwin-limit").is_some());
}

// ---- swivel (CYCLE800) ----

#[tokio::test]
async fn the_swivel_endpoint_turns_the_head_from_jog_and_returns_to_jog() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    let mode = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(mode.status, StatusCode::OK, "{}", mode.body);
    let body = json!({"data_set": "HEAD_CA", "mode": "axis_by_axis", "sequence": "XYZ", "a": 30,
        "direction": 1, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["alarms"], json!([]), "{}", reply.body);
    assert_eq!(reply.body["mode"], "JOG");
    assert!((pos(&reply.body, "machine", "A") - 30.0).abs() < 1e-9, "{}", reply.body);
    // Minus: the lower A (the head's direction reference), C half a turn away.
    let body = json!({"data_set": "HEAD_CA", "mode": "axis_by_axis", "a": 30, "direction": -1,
        "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert!((pos(&reply.body, "machine", "A") + 30.0).abs() < 1e-9, "{}", reply.body);
}

#[tokio::test]
async fn swivel_parameters_that_do_not_fit_are_400_or_an_alarm_without_motion() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    for body in [
        json!({"mode": "axis_by_axis", "sequence": "XYX"}),
        json!({"mode": "direct", "retract": 3}),
        json!({"mode": "direct", "retract": 5, "retract_distance": -2}),
        json!({"mode": "sideways"}),
    ] {
        let reply = server.post(&format!("/sessions/{id}/swivel"), body.clone()).await;
        assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{body}: {}", reply.body);
    }
    // A = 120 lies beyond the head's ±110°: the cycle's alarm 61184, nothing moves.
    let body = json!({"data_set": "HEAD_CA", "mode": "direct", "a": 0, "b": 120, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["alarms"][0]["number"], 61184, "{}", reply.body);
    assert_eq!(pos(&reply.body, "machine", "A"), 0.0);
}
