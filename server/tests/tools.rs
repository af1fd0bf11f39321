//! The tool list over REST: `GET/PUT /sessions/{id}/tools`, loading and unloading tools, the
//! state's tool name and prepared tool, and the list surviving a restart.

use crate::common;

use common::{Server, error_message, pos};
use nctwin_server::Config;
use reqwest::StatusCode;
use serde_json::{Value, json};

fn tool(list: &Value, number: u64) -> &Value {
    list["tools"].as_array().unwrap().iter().find(|t| t["number"] == number).unwrap_or_else(|| panic!("no T{number}"))
}

#[tokio::test]
async fn the_preset_tool_list_has_names_edges_and_magazine_places() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let list = server.get(&format!("/sessions/{id}/tools")).await.body;
    let drill = tool(&list, 2);
    assert_eq!(drill["name"], "DRILL_8");
    assert_eq!(drill["place"], json!({"magazine": 1, "place": 2}));
    assert_eq!(drill["edges"][0]["type"], 200.0);
    assert_eq!(drill["edges"][0]["lengths"], json!([120.0, 0.0, 0.0]));
    assert_eq!(drill["edges"][0]["radius"], 4.0);
    let chain = &list["magazines"][0];
    assert_eq!((chain["number"].clone(), chain["kind"].clone()), (json!(1), json!(1)));
    assert_eq!(chain["places"].as_array().unwrap().len(), 12);
    assert_eq!(list["spindle"], 0);
}

#[tokio::test]
async fn a_put_tool_without_a_place_lands_in_a_free_place_and_a_program_selects_it_by_name() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut list = server.get(&format!("/sessions/{id}/tools")).await.body;
    list["tools"].as_array_mut().unwrap().push(json!({
        "number": 7, "name": "TAP_M6", "duplo": 1,
        "edges": [{"d": 1, "type": 240.0, "lengths": [80.0, 0.0, 0.0], "radius": 3.0}]
    }));
    let reply = server.put(&format!("/sessions/{id}/tools"), list).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let tap = tool(&reply.body, 7);
    // Places 1 and 2 hold T1 and T2: the tap goes into place 3, and the list says why.
    assert_eq!((tap["place"].clone(), tap["auto_placed"].clone()), (json!({"magazine": 1, "place": 3}), json!(true)));

    // T="TAP_M6" changes at once (MD22550 = 0); Z5 with its length 80: machine Z 85.
    let reply = server
        .post(
            &format!("/sessions/{id}/run"),
            json!({"program": "T=\"TAP_M6\"\nG0 X0 Y0 Z5\nM30", "pace": "fast", "wait": true}),
        )
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["alarms"], json!([]));
    assert_eq!(reply.body["tool"], json!({"t": 7, "d": 1, "name": "TAP_M6", "prepared": 7}));
    assert!((pos(&reply.body, "machine", "Z") - 85.0).abs() < 1e-9, "{}", reply.body);
    let list = server.get(&format!("/sessions/{id}/tools")).await.body;
    assert_eq!((list["spindle"].clone(), tool(&list, 7)["in_spindle"].clone()), (json!(7), json!(true)));
}

#[tokio::test]
async fn bad_tool_data_is_a_400_naming_the_field_and_changes_nothing() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let before = server.get(&format!("/sessions/{id}/tools")).await.body;
    let put = |body: Value| {
        let server = &server;
        let id = id.clone();
        async move { server.put(&format!("/sessions/{id}/tools"), body).await }
    };
    let mut bad = before.clone();
    bad["tools"][1]["edges"][0]["d"] = json!(13);
    let message = error_message(&put(bad).await, StatusCode::BAD_REQUEST);
    assert!(message.contains("tools[1].edges[0].d") && message.contains("1..12"), "{message}");
    let mut bad = before.clone();
    bad["tools"][1]["place"] = json!({"magazine": 1, "place": 1});
    let message = error_message(&put(bad).await, StatusCode::BAD_REQUEST);
    assert!(message.starts_with("tools[1].place:") && message.contains("already holds tool 1"), "{message}");
    let mut bad = before.clone();
    bad["tools"][0]["place"] = json!({"magazine": 10000, "place": 1});
    let message = error_message(&put(bad).await, StatusCode::BAD_REQUEST);
    assert!(message.starts_with("tools[0].place:") && message.contains("magazine number"), "{message}");
    let mut bad = before.clone();
    bad["tools"][0]["colour"] = json!("red");
    let message = error_message(&put(bad).await, StatusCode::BAD_REQUEST);
    assert!(message.contains("colour"), "{message}");
    assert_eq!(server.get(&format!("/sessions/{id}/tools")).await.body, before);
}

#[tokio::test]
async fn tools_are_unloaded_and_loaded_and_the_list_survives_a_restart() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post_empty(&format!("/sessions/{id}/tools/DRILL_8/unload")).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(tool(&reply.body, 2)["place"], json!({"magazine": 9999, "place": 1}));
    let reply = server.post(&format!("/sessions/{id}/tools/DRILL_8/load"), json!({"magazine": 1, "place": 7})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(tool(&reply.body, 2)["place"], json!({"magazine": 1, "place": 7}));
    let message = error_message(
        &server.post(&format!("/sessions/{id}/tools/MILL_D10/load"), json!({"magazine": 1, "place": 7})).await,
        StatusCode::BAD_REQUEST,
    );
    assert!(message.contains("holds tool 2"), "{message}");
    let message = error_message(
        &server.post_empty(&format!("/sessions/{id}/tools/NO_SUCH/unload")).await,
        StatusCode::BAD_REQUEST,
    );
    assert!(message.contains("no tool named NO_SUCH"), "{message}");

    let dir = server.stop().await;
    let server = Server::start_config(Config::new(dir, common::WEB_DIR)).await;
    let list = server.get(&format!("/sessions/{id}/tools")).await.body;
    assert_eq!(tool(&list, 2)["place"], json!({"magazine": 1, "place": 7}));
}

#[tokio::test]
async fn tool_monitoring_shows_in_the_list_the_counted_life_and_the_disabled_state() {
    // MILL_D10 time-monitored with 0.5 min left: 36 s of G1 at F100 (X0 to X60) use 0.6 min,
    // so the list shows -0.1 min left, $TC_TP8 = 2 (enabled) + 4 (disabled), and the state
    // alarm 6413 (information: the program ran to its end).
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut list = server.get(&format!("/sessions/{id}/tools")).await.body;
    let mill = list["tools"].as_array_mut().unwrap().iter_mut().find(|t| t["number"] == 1).unwrap();
    mill["monitoring"] = json!(1);
    mill["edges"][0]["monitoring"] = json!({"2": 0.5});
    let reply = server.put(&format!("/sessions/{id}/tools"), list).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let program = "T=\"MILL_D10\"\nG0 X0 Y0 Z50\nG1 F100 X60\nM30";
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let alarms: Vec<_> = reply.body["alarms"].as_array().unwrap().iter().map(|a| a["number"].clone()).collect();
    assert_eq!(alarms, vec![json!(6413)], "{}", reply.body);
    let list = server.get(&format!("/sessions/{id}/tools")).await.body;
    let mill = tool(&list, 1);
    assert_eq!(mill["state"], 6);
    let left = mill["edges"][0]["monitoring"]["2"].as_f64().unwrap();
    assert!((left + 0.1).abs() < 1e-4, "{left}");
}
