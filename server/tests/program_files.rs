//! Files a part program writes with the file functions (WRITE, DELETE) are programs of the
//! session: listed, readable over REST, saved with the checkpoint and back after a restart,
//! whatever their text (a log need not be a program).

mod common;

use common::Server;
use nctwin_server::Config;
use reqwest::StatusCode;
use serde_json::json;

async fn restart(server: Server) -> Server {
    let dir = server.stop().await;
    Server::start_config(Config::new(dir, common::WEB_DIR)).await
}

#[tokio::test]
async fn a_file_written_by_a_program_is_listed_and_survives_a_restart() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(server.put(&format!("/sessions/{id}/programs/OLD"), json!({"text": "M17"})).await.status, StatusCode::OK);
    // The log's second line is no NC block: a file keeps any text.
    let program = "DEF INT E\nR1=12.5\nWRITE(E, \"/_N_MPF_DIR/_N_SHIFTLOG_MPF\", \"; PART 1\")\n\
                   WRITE(E, \"SHIFTLOG\", SPRINT(\"RESULT: %.1F mm\", R1))\nDELETE(E, \"OLD\")\nM30";
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);

    // "; PART 1\n" is 9 bytes, "RESULT: 12.5 mm\n" 16: 25.
    let log = "; PART 1\nRESULT: 12.5 mm\n";
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "SHIFTLOG", "size": 25}]));
    let text = server.get(&format!("/sessions/{id}/programs/SHIFTLOG")).await.body;
    assert_eq!(text, json!({"name": "SHIFTLOG", "text": log}));

    let server = restart(server).await;
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "SHIFTLOG", "size": 25}]), "OLD stays deleted, the log is back");
    let text = server.get(&format!("/sessions/{id}/programs/SHIFTLOG")).await.body;
    assert_eq!(text, json!({"name": "SHIFTLOG", "text": log}));

    // The next run appends to the restored file.
    let reply = server
        .post(
            &format!("/sessions/{id}/run"),
            json!({"program": "DEF INT E\nWRITE(E, \"SHIFTLOG\", \"; PART 2\")\nM30", "pace": "fast", "wait": true}),
        )
        .await;
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    let text = server.get(&format!("/sessions/{id}/programs/SHIFTLOG")).await.body;
    assert_eq!(text["text"], format!("{log}; PART 2\n"));
}
