//! Files a part program writes with the file functions (WRITE, DELETE) are programs of the
//! session: listed, readable over REST, saved with the checkpoint and back after a restart,
//! whatever their text (a log need not be a program).

use crate::common;

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
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/OLD"), json!({"text": "M17"})).await.status,
        StatusCode::OK
    );
    // The log's second line is no NC block: a file keeps any text.
    let program = "DEF INT ERR\nR1=12.5\nWRITE(ERR, \"/_N_MPF_DIR/_N_SHIFTLOG_MPF\", \"; PART 1\")\n\
                   WRITE(ERR, \"SHIFTLOG\", SPRINT(\"RESULT: %.1F mm\", R1))\nDELETE(ERR, \"OLD\")\nM30";
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
            json!({"program": "DEF INT ERR\nWRITE(ERR, \"SHIFTLOG\", \"; PART 2\")\nM30", "pace": "fast", "wait": true}),
        )
        .await;
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    let text = server.get(&format!("/sessions/{id}/programs/SHIFTLOG")).await.body;
    assert_eq!(text["text"], format!("{log}; PART 2\n"));
}

/// `nctwin simulate` on a data file: a `.INI` file (with or without its `%_N_..._INI` header)
/// runs as the control runs it, loading its data; a datum it cannot take is an error with the
/// file's own line number.
#[test]
fn simulate_runs_an_ini_file_as_the_control_does() {
    use std::process::Command;
    let dir = std::env::temp_dir().join(format!("nctwin-ini-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        Command::new(env!("CARGO_BIN_EXE_nctwin"))
            .args(["simulate", "--machine", "mill-3axis", path.to_str().unwrap()])
            .output()
            .expect("nctwin runs")
    };
    let out = run("TOA.INI", "CHANDATA(1)\r\nINCH\r\n$TC_DP1[1,1]=120\r\n$TC_DP3[1,1]=4\r\nM17\r\n");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run("ARCH.INI", "%_N_TOA_INI\n;$PATH=/_N_TOA_DIR\nCHANDATA(1)\nINCH\n$TC_DP3[1,1]=4\nM17\n");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["outcome"], "ended");
    // Line 3 of the file: machine data after INCH is refused (not converted).
    let out = run("BAD.INI", "CHANDATA(1)\nINCH\n$MA_POS_LIMIT_PLUS[AX1]=3\nM17\n");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 3: $MA_POS_LIMIT_PLUS after INCH"));
    std::fs::remove_dir_all(&dir).ok();
}
