//! Roles and tokens: who may read and who may drive a session.
//!
//! Creating a session makes three tokens, one per [`Role`]: the owner's and two to share
//! (operator, observer). Each is 128 bits from the operating system's CSPRNG, written as
//! `nct_` + 32 lowercase hex digits. The server keeps only their SHA-256 hashes, so the tokens are
//! shown once, in the reply that creates the session.
//!
//! [`AuthMode::Off`] (the default, a local single-user server): no request needs a token and the
//! API works exactly as without this module. [`AuthMode::Required`]: every request to a session
//! needs `Authorization: Bearer <token>` (the WebSocket stream may pass `?token=` instead, as
//! browsers cannot set headers on a WebSocket), and what it may do follows from the role (see
//! [`access`]).

pub mod access;
pub mod who;

use std::fmt;

use sha2::{Digest, Sha256};

use crate::storage::TokenHashes;

/// Whether requests to sessions need tokens.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum AuthMode {
    /// No tokens needed: every client may do everything (the default, for a local server).
    #[default]
    Off,
    /// Every session request needs a token of that session; roles apply.
    Required,
}

/// A client's role in one session.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, utoipa::ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// Reads everything, changes nothing.
    Observer,
    /// Drives the channel while holding control.
    Operator,
    /// Created the session: drives it, can always take control back, may delete it.
    Owner,
}

impl fmt::Display for Role {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Role::Observer => "observer",
            Role::Operator => "operator",
            Role::Owner => "owner",
        })
    }
}

/// Prefix of every token: makes them recognisable to people and secret scanners.
pub const TOKEN_PREFIX: &str = "nct_";

/// The three tokens of a new session, in clear (returned once to the creator).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TokenSet {
    pub owner: String,
    pub operator: String,
    pub observer: String,
}

impl TokenSet {
    /// Three fresh tokens from the operating system's CSPRNG.
    pub fn generate() -> Result<TokenSet, getrandom::Error> {
        Ok(TokenSet { owner: new_token()?, operator: new_token()?, observer: new_token()? })
    }

    /// The hashes that are stored and compared.
    pub fn hashes(&self) -> TokenHashes {
        TokenHashes { owner: hash(&self.owner), operator: hash(&self.operator), observer: hash(&self.observer) }
    }
}

/// One token: [`TOKEN_PREFIX`] + 128 random bits as 32 hex digits.
fn new_token() -> Result<String, getrandom::Error> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes)?;
    Ok(format!("{TOKEN_PREFIX}{}", hex(&bytes)))
}

/// SHA-256 of a token as lowercase hex. A fast hash is enough: the tokens are random with 128
/// bits, so there is nothing to guess that a slow password hash would protect.
pub fn hash(token: &str) -> String {
    hex(&Sha256::digest(token.as_bytes()))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The role a presented token gives in a session with these hashes, if any.
pub fn role_of(hashes: &TokenHashes, token: &str) -> Option<Role> {
    let presented = hash(token);
    // Compare every hash, each in constant time, so timing tells nothing about which matched.
    let owner = constant_time_eq(&presented, &hashes.owner);
    let operator = constant_time_eq(&presented, &hashes.operator);
    let observer = constant_time_eq(&presented, &hashes.observer);
    if owner {
        Some(Role::Owner)
    } else if operator {
        Some(Role::Operator)
    } else if observer {
        Some(Role::Observer)
    } else {
        None
    }
}

fn constant_time_eq(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_have_128_random_bits_and_differ() {
        let set = TokenSet::generate().expect("random");
        for t in [&set.owner, &set.operator, &set.observer] {
            let digits = t.strip_prefix(TOKEN_PREFIX).expect("prefix");
            assert_eq!(digits.len(), 32);
            assert!(digits.bytes().all(|b| b.is_ascii_hexdigit() && !b.is_ascii_uppercase()), "{t}");
        }
        assert!(set.owner != set.operator && set.operator != set.observer && set.owner != set.observer);
        assert_ne!(TokenSet::generate().expect("random").owner, set.owner);
    }

    #[test]
    fn a_token_maps_to_its_role_and_others_to_none() {
        let set = TokenSet::generate().expect("random");
        let hashes = set.hashes();
        assert_eq!(role_of(&hashes, &set.owner), Some(Role::Owner));
        assert_eq!(role_of(&hashes, &set.operator), Some(Role::Operator));
        assert_eq!(role_of(&hashes, &set.observer), Some(Role::Observer));
        assert_eq!(role_of(&hashes, "nct_00000000000000000000000000000000"), None);
        assert_eq!(role_of(&hashes, ""), None);
        assert_eq!(hashes.owner.len(), 64, "SHA-256 in hex");
    }
}
