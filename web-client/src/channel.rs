//! Where a match's messages come from and go to: the server, through the
//! self-healing socket ([`Connection`]), or a match against the computer
//! played in this page ([`LocalMatch`]). The Play screen holds one and
//! treats both alike: it sends the player's messages and polls for the
//! match's, whichever side of the network the rules run on.

use crate::connection::{Connection, Link};
use crate::local_match::LocalMatch;
use game::protocol::{ClientMessage, ServerMessage};

/// A match's messages: the server's, or this page's own.
pub enum Channel {
    /// The match is played on the server.
    Server(Connection),
    /// The match is played here, offline.
    Local(Box<LocalMatch>),
}

impl Channel {
    /// Sends the player's message; `false` if it could not go (the caller
    /// tells the player; nothing is queued behind their back).
    pub fn send(&mut self, m: &ClientMessage) -> bool {
        match self {
            Channel::Server(c) => c.send(m),
            Channel::Local(l) => l.send(m),
        }
    }

    /// The match's messages since the last poll, at clock time `now`
    /// (seconds).
    pub fn poll(&mut self, now: f64) -> Vec<ServerMessage> {
        match self {
            Channel::Server(c) => c.poll(now),
            Channel::Local(l) => l.poll(now),
        }
    }

    /// Where the channel stands, for the status line.
    pub fn link(&self) -> &Link {
        match self {
            Channel::Server(c) => c.link(),
            Channel::Local(_) => &Link::Offline,
        }
    }

    /// Whether messages can go now (always, offline).
    pub fn is_open(&self) -> bool {
        match self {
            Channel::Server(c) => c.is_open(),
            Channel::Local(_) => true,
        }
    }

    /// The socket's address, as last opened (none offline).
    pub fn url(&self) -> Option<&str> {
        match self {
            Channel::Server(c) => Some(c.url()),
            Channel::Local(_) => None,
        }
    }

    /// The match played here, if it is.
    pub fn local(&self) -> Option<&LocalMatch> {
        match self {
            Channel::Local(l) => Some(l),
            Channel::Server(_) => None,
        }
    }

    /// The match played here, to drive, if it is.
    pub fn local_mut(&mut self) -> Option<&mut LocalMatch> {
        match self {
            Channel::Local(l) => Some(l),
            Channel::Server(_) => None,
        }
    }
}
