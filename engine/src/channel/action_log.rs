//! The action log: operator commands as events, in order with what the channel does, so every
//! screen watching a session can say who did what (as Operate's action log records operator
//! actions). The shell names the command and the operator; the channel only passes them on.

use super::{Channel, Event};

/// One operator command: what was done, by which role and which display name.
#[derive(Debug, Clone, PartialEq)]
pub struct OperatorAction {
    /// The command, e.g. `POST start`, `PUT mode`.
    pub action: String,
    /// The role it was done in: `owner`, `operator`.
    pub role: String,
    /// The display name the user gave when joining (empty when none).
    pub name: String,
}

impl Channel {
    /// Records an operator's command as an [`Event::OperatorAction`].
    pub fn log_operator_action(&mut self, action: OperatorAction) {
        self.events.push(Event::OperatorAction(action));
    }
}
