//! Archive files over HTTP: `POST .../program-archive` stores every program of an archive in
//! the directory of its `;$PATH=` line and loads its NC data sections (`_N_TOA_INI`) as the
//! control does, `GET .../program-archive` writes the session's programs back in the same
//! format, and NC data files load through `PUT .../machine-data` too.

use crate::common;

use common::{Server, pos};
use reqwest::StatusCode;
use serde_json::json;

/// A main program in a workpiece folder calling a subprogram of the same archive, CRLF line
/// ends, Cyrillic and German comments, and a tool-data section.
const ARCHIVE: &str = "%_N_FLANGE_MPF\r\n;$PATH=/_N_WKS_DIR/_N_FLANGE_WPD\r\n; Фланец, Außenkontur\r\nG0 X10 Y5\r\n\
                       POCKET\r\nM30\r\n%_N_POCKET_SPF\r\n;$PATH=/_N_SPF_DIR\r\nG91 G0 X7\r\nG90\r\nM17\r\n\
                       %_N_TOA_INI\r\nCHANDATA(1)\r\n$TC_DP1[1,1]=120\r\n$TC_DP3[1,1]=77.5\r\nM17\r\n";

async fn import(server: &Server, id: &str, body: impl Into<reqwest::Body>) -> common::Reply {
    let url = server.url(&format!("/sessions/{id}/program-archive"));
    server.send(server.client.post(url).header("content-type", "text/plain").body(body)).await
}

async fn export(server: &Server, id: &str) -> (StatusCode, String) {
    let response =
        server.client.get(server.url(&format!("/sessions/{id}/program-archive"))).send().await.expect("sent");
    let status = response.status();
    (status, response.text().await.expect("text"))
}

#[tokio::test]
async fn an_archive_stores_each_program_under_its_name_and_the_main_program_calls_the_other() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = import(&server, &id, ARCHIVE).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(
        reply.body,
        json!({
            "programs": [
                {"name": "/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE", "type": "MPF", "directory": "/_N_WKS_DIR/_N_FLANGE_WPD", "size": 54},
                {"name": "POCKET", "type": "SPF", "directory": "/_N_SPF_DIR", "size": 21},
            ],
            "nc_data": [{"name": "TOA_INI", "line": 12}],
            "skipped": [],
        })
    );
    // Listed with their directories.
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE", "size": 54}, {"name": "POCKET", "size": 21}]));
    let flange = server.get(&format!("/sessions/{id}/programs/FLANGE")).await.body;
    assert_eq!(flange["text"], "; Фланец, Außenkontur\r\nG0 X10 Y5\r\nPOCKET\r\nM30\r\n");
    // X10, then POCKET moves 7 more. FLANGE lives in its workpiece folder: a run outside every
    // directory reaches it through CALLPATH, as on the control.
    let run = json!({"program": "CALLPATH(\"/_N_WKS_DIR/_N_FLANGE_WPD\")\nFLANGE\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(state["status"], "idle", "{state}");
    assert_eq!((pos(&state, "workpiece", "X"), pos(&state, "workpiece", "Y")), (17.0, 5.0));
}

#[tokio::test]
async fn export_writes_the_archive_format_back() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(import(&server, &id, ARCHIVE).await.status, StatusCode::OK);
    let (status, text) = export(&server, &id).await;
    assert_eq!(status, StatusCode::OK);
    // By name, each in its directory.
    assert_eq!(
        text,
        "%_N_FLANGE_MPF\n;$PATH=/_N_WKS_DIR/_N_FLANGE_WPD\n; Фланец, Außenkontur\r\nG0 X10 Y5\r\nPOCKET\r\nM30\r\n\
         %_N_POCKET_SPF\n;$PATH=/_N_SPF_DIR\nG91 G0 X7\r\nG90\r\nM17\r\n"
    );
    // And it reads back in.
    let again = server.session("mill-3axis").await;
    let reply = import(&server, &again, text).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["programs"][1]["directory"], "/_N_SPF_DIR");
}

#[tokio::test]
async fn a_legacy_encoded_archive_is_decoded() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let text = "%_N_GBK_MPF\r\n; 加工程序 法兰盘 粗加工\r\nMSG(\"请安装毛坯并检查刀具\")\r\nM30\r\n";
    let (bytes, _, _) = encoding_rs::GBK.encode(text);
    let reply = import(&server, &id, bytes.into_owned()).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let stored = server.get(&format!("/sessions/{id}/programs/GBK")).await.body;
    assert_eq!(stored["text"], "; 加工程序 法兰盘 粗加工\r\nMSG(\"请安装毛坯并检查刀具\")\r\nM30\r\n");
}

#[tokio::test]
async fn a_broken_archive_stores_nothing() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let broken = "%_N_GOOD_MPF\nG0 X1\nM30\n%_N_BAD_SPF\nG1 X=\nM17\n";
    let reply = import(&server, &id, broken).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    assert_eq!(reply.body["line"], 5, "the archive's line of the error");
    assert!(reply.body["error"].as_str().unwrap().starts_with("program BAD line 1 (archive line 5)"), "{}", reply.body);
    let twice = "%_N_A_MPF\nM30\n%_N_A_SPF\nM17\n";
    let reply = import(&server, &id, twice).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    assert_eq!(reply.body["line"], 3);
    let reply = import(&server, &id, "G0 X1\nM30\n").await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "not an archive: {}", reply.body);
    assert_eq!(server.get(&format!("/sessions/{id}/programs")).await.body, json!([]));
}

#[tokio::test]
async fn a_failed_store_half_way_puts_the_programs_back() {
    // 100 bytes per session: the second program does not fit.
    let limits = nctwin_server::Limits { session_program_bytes: 100, ..Default::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/A"), json!({"text": "G0 X1"})).await.status,
        StatusCode::OK
    );
    let archive = format!("%_N_A_MPF\nG0 X2\n%_N_B_MPF\n;{}\nM30\n", "x".repeat(120));
    let reply = import(&server, &id, archive).await;
    assert_eq!(reply.status, StatusCode::PAYLOAD_TOO_LARGE, "{}", reply.body);
    assert_eq!(server.get(&format!("/sessions/{id}/programs/A")).await.body["text"], "G0 X1");
    assert_eq!(server.get(&format!("/sessions/{id}/programs/B")).await.status, StatusCode::NOT_FOUND);
}

#[tokio::test]
async fn a_tool_data_file_loads_as_machine_data_with_its_tool_management_lines() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let toa = "%_N_TOA_INI\r\n;$PATH=/_N_INITIAL_INI\r\nCHANDATA(1)\r\nMETRIC\r\n$TC_TP1[1]=1\r\n\
               $TC_TP2[1]=\"FRAESER_10\"\r\n$TC_DP1[1,1]=120\r\n$TC_DP3[1,1]=100.5\r\n$TC_DP6[1,1]=5\r\n\
               $TC_MPP1[1,1]=1\r\n$P_UIFR[1]=CTRANS(X,10,Y,20,Z,30)\r\nM17\r\n";
    let url = server.url(&format!("/sessions/{id}/machine-data"));
    let reply = server.send(server.client.put(url).json(&json!({ "text": toa }))).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let ignored: Vec<_> =
        reply.headers.get_all("nctwin-nc-data-ignored").iter().map(|v| v.to_str().unwrap().to_string()).collect();
    // $TC_TP and $TC_MPP are tool management data NCTwin keeps: nothing is ignored, and T1
    // carries the file's name.
    assert!(ignored.is_empty(), "{ignored:?}");
    let tools = server.get(&format!("/sessions/{id}/tools")).await.body;
    assert_eq!(tools["tools"][0]["name"], "FRAESER_10", "{tools}");
    // G54 = $P_UIFR[1] moves the zero point by (10, 20, 30); T1 D1 adds the length 100.5 in Z.
    let run = json!({"program": "G54 T1 D1\nG0 X0 Y0 Z0\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(state["status"], "idle", "{state}");
    assert_eq!(
        (pos(&state, "machine", "X"), pos(&state, "machine", "Y"), pos(&state, "machine", "Z")),
        (10.0, 20.0, 130.5)
    );
}

#[tokio::test]
async fn the_nc_data_of_an_archive_are_loaded() {
    // The TOA section sets T1 D1's length to 77.5: T1 D1 at Z10 puts the machine Z at 87.5.
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = import(&server, &id, ARCHIVE).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let run = json!({"program": "T1 D1\nG0 X0 Y0 Z10\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(state["status"], "idle", "{state}");
    assert_eq!(pos(&state, "machine", "Z"), 87.5);
}

#[tokio::test]
async fn bad_nc_data_name_their_archive_line_and_store_nothing() {
    // The datum on archive line 6 does not exist: 400 with that line, no program kept.
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let archive = "%_N_A_MPF\nG0 X1\nM30\n%_N_TOA_INI\nCHANDATA(1)\n$TC_DP99[1,1]=1\nM17\n";
    let reply = import(&server, &id, archive).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    assert_eq!(reply.body["line"], 6, "{}", reply.body);
    assert_eq!(server.get(&format!("/sessions/{id}/programs")).await.body, json!([]));
}

#[tokio::test]
async fn programs_keep_their_directories_across_a_restart() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(import(&server, &id, ARCHIVE).await.status, StatusCode::OK);
    let dir = server.stop().await;
    let server = Server::start_config(nctwin_server::Config::new(dir, common::WEB_DIR)).await;
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE", "size": 54}, {"name": "POCKET", "size": 21}]));
    // The stored name reads back (the path URL-encoded), and the export keeps the folder.
    let flange = server.get(&format!("/sessions/{id}/programs/%2F_N_WKS_DIR%2F_N_FLANGE_WPD%2FFLANGE")).await;
    assert_eq!(flange.status, StatusCode::OK, "{}", flange.body);
    assert_eq!(flange.body["text"], "; Фланец, Außenkontur\r\nG0 X10 Y5\r\nPOCKET\r\nM30\r\n");
    let (_, text) = export(&server, &id).await;
    assert!(text.starts_with("%_N_FLANGE_MPF\n;$PATH=/_N_WKS_DIR/_N_FLANGE_WPD\n"), "{text}");
    // Deleting by the stored name removes that one program (the subprogram directory's
    // programs are the session's flat store: their stored name is the bare name).
    let url = server.url(&format!("/sessions/{id}/programs/POCKET"));
    let deleted = server.client.delete(url).send().await.expect("sent").status();
    assert_eq!(deleted, StatusCode::NO_CONTENT);
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE", "size": 54}]));
}
