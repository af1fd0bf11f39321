//! `GET/PUT /sessions/{id}/kinematic-chains`: a session's chain data out and back in as a part
//! program in plain text; a bad line is a 400 that names it and changes nothing.

use crate::common;

use common::{Server, error_message};
use reqwest::StatusCode;

/// A minimal chain: X, Y, Z on the tool side of the mill5-head-ca machine, C and A of its fork
/// head, and a TRAORI_DYN record using them.
const CHAIN: &str = r#"; fork head C-A
N10 DELOBJ("TRAFO_DATA")
N20 DELOBJ("KIN_CHAIN_ELEM")
$NK_NAME[0]="ROOT"
$NK_TYPE[0]="OFFSET"
$NK_NEXT[0]="X axis"
$NK_NAME[1]="X axis"
$NK_TYPE[1]="AXIS_LIN"
$NK_NEXT[1]="Y axis"
$NK_OFF_DIR[1,0]=1
$NK_AXIS[1]="X"
$NK_NAME[2]="Y axis"
$NK_TYPE[2]="AXIS_LIN"
$NK_NEXT[2]="Z axis"
$NK_OFF_DIR[2,1]=1
$NK_AXIS[2]="Y"
$NK_NAME[3]="Z axis"
$NK_TYPE[3]="AXIS_LIN"
$NK_NEXT[3]="C axis"
$NK_OFF_DIR[3,2]=1
$NK_AXIS[3]="Z"
$NK_NAME[4]="C axis"
$NK_TYPE[4]="AXIS_ROT"
$NK_NEXT[4]="A axis"
$NK_OFF_DIR[4,2]=1
$NK_AXIS[4]="C"
$NK_NAME[5]="A axis"
$NK_TYPE[5]="AXIS_ROT"
$NK_NEXT[5]="Spindle"
$NK_OFF_DIR[5,0]=1
$NK_AXIS[5]="A"
$NK_NAME[6]="Spindle"
$NK_TYPE[6]="OFFSET"
$NK_OFF_DIR[6,2]=-150
$NT_NAME[1]="Fork head"
$NT_TRAFO_TYPE[1]="TRAORI_DYN"
$NT_T_CHAIN_LAST_ELEM[1]="Spindle"
$NT_ROT_AX_NAME[1,0]="C axis"
$NT_ROT_AX_NAME[1,1]="A axis"
$NT_GEO_AX_NAME[1,0]="X axis"
$NT_GEO_AX_NAME[1,1]="Y axis"
$NT_GEO_AX_NAME[1,2]="Z axis"
NEWCONF
"#;

async fn get_text(server: &Server, id: &str) -> (StatusCode, Option<String>, String) {
    let response = reqwest::Client::new()
        .get(server.url(&format!("/sessions/{id}/kinematic-chains")))
        .send()
        .await
        .expect("request sent");
    let status = response.status();
    let content_type = response.headers().get("content-type").map(|v| v.to_str().unwrap_or("").to_string());
    (status, content_type, response.text().await.expect("body"))
}

async fn put_text(server: &Server, id: &str, text: &str) -> common::Reply {
    let request = reqwest::Client::new()
        .put(server.url(&format!("/sessions/{id}/kinematic-chains")))
        .header("content-type", "text/plain")
        .body(text.to_string());
    server.send(request).await
}

#[tokio::test]
async fn chain_data_goes_out_and_back_in_as_a_program() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    let (status, content_type, empty) = get_text(&server, &id).await;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.is_some_and(|c| c.starts_with("text/plain")));
    assert_eq!(
        empty,
        "; Kinematic chain elements ($NK_) and transformations defined by kinematic chains ($NT_)\nDELOBJ(\"TRAFO_DATA\")\nDELOBJ(\"KIN_CHAIN_ELEM\")\nNEWCONF\n"
    );

    let reply = put_text(&server, &id, CHAIN).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let (_, _, exported) = get_text(&server, &id).await;
    assert!(exported.contains("$NK_OFF_DIR[6,2]=-150.0\n$NT_NAME[1]=\"Fork head\"\n"), "{exported}");
    // The export also sits in the session's NC data, and a second session takes it unchanged.
    let md = server.get(&format!("/sessions/{id}/machine-data")).await.body["text"].clone();
    assert!(md.as_str().is_some_and(|t| t.contains("$NT_TRAFO_TYPE[1]=\"TRAORI_DYN\"")), "{md}");
    let other = server.session("mill5-head-ca").await;
    assert_eq!(put_text(&server, &other, &exported).await.status, StatusCode::OK);
    assert_eq!(get_text(&server, &other).await.2, exported);
}

#[tokio::test]
async fn a_bad_chain_program_is_a_400_naming_its_line_and_changes_nothing() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    assert_eq!(put_text(&server, &id, CHAIN).await.status, StatusCode::OK);
    let before = get_text(&server, &id).await.2;
    let bad = CHAIN.replace("$NK_TYPE[3]=\"AXIS_LIN\"", "G1 X10");
    let reply = put_text(&server, &id, &bad).await;
    let message = error_message(&reply, StatusCode::BAD_REQUEST);
    assert_eq!(reply.body["line"], 18, "{}", reply.body);
    assert!(message.contains("G1 X10") && message.contains("only $NK_/$NT_ assignments"), "{message}");
    let reply = put_text(&server, &id, &CHAIN.replace("$NK_AXIS[5]=\"A\"", "$NK_AXIS[5]=\"W\"")).await;
    let message = error_message(&reply, StatusCode::BAD_REQUEST);
    assert!(message.contains("$NK_AXIS \"W\" is no machine or channel axis"), "{message}");
    assert_eq!(get_text(&server, &id).await.2, before);
    let message = error_message(&put_text(&server, "nope", CHAIN).await, StatusCode::NOT_FOUND);
    assert!(message.contains("nope"), "{message}");
}

#[tokio::test]
async fn a_corrtrafo_correction_is_in_the_export() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    assert_eq!(put_text(&server, &id, CHAIN).await.status, StatusCode::OK);
    // A's direction (element 5, orientation axis 1) corrected to (1, 0.01, 0): 0.57°, inside
    // SD41611's 1°. The program's correction is what the archive carries afterwards.
    let program =
        "DEF REAL VEC[3]\nVEC[0]=1\nVEC[1]=0.01\nTRAFOON(\"Fork head\")\nR1=CORRTRAFO(1, 1, VEC)\nTRAFOOF\nM30";
    let body = serde_json::json!({"program": program, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/run"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    let (_, _, exported) = get_text(&server, &id).await;
    assert!(exported.contains("$NK_OFF_DIR[5,0]=1.0\n$NK_OFF_DIR[5,1]=0.01\n"), "{exported}");
}
