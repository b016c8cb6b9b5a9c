//! Relay sequencing: how the node of a client hands its relayed
//! connections what their match's owner sent them. The owner numbers each
//! connection's messages from 0; the client's node forwards them strictly
//! in that order. A duplicate (an already forwarded number) is dropped; a
//! gap (a message lost by pub/sub) or a client too slow to take one more
//! ends the connection, so its client reconnects and starts again from the
//! full `match-state`: a client never sees a gap or a duplicate. No I/O:
//! [`Links::deliver`] only moves messages into the connections' queues.

use crate::play::room::Outbound;
use bytestring::ByteString;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;
use tokio::sync::mpsc;

/// Where a numbered message stands against the number a connection
/// expects next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Order {
    /// Already forwarded: dropped.
    Duplicate,
    /// The one expected: forwarded.
    Next,
    /// Later than expected: one before it was lost.
    Gap,
}

/// The numbers of one relayed connection's messages.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Sequence {
    /// The number the next message must carry.
    next: u64,
}

impl Sequence {
    /// Where `seq` stands (nothing changes).
    pub fn order(&self, seq: u64) -> Order {
        match seq.cmp(&self.next) {
            std::cmp::Ordering::Less => Order::Duplicate,
            std::cmp::Ordering::Equal => Order::Next,
            std::cmp::Ordering::Greater => Order::Gap,
        }
    }

    /// The expected message was forwarded: expect the one after it.
    pub fn advance(&mut self) {
        self.next += 1;
    }

    /// The number expected next.
    pub fn expected(&self) -> u64 {
        self.next
    }
}

/// A relayed connection, as its client's node holds it.
pub(super) struct LinkEnd {
    pub tx: mpsc::Sender<Outbound>,
    pub sequence: Sequence,
    /// How many of the connection's messages the owner's room refused.
    pub refused: Arc<AtomicU32>,
}

impl LinkEnd {
    /// A connection's end before its first message.
    pub fn new(tx: mpsc::Sender<Outbound>, refused: Arc<AtomicU32>) -> LinkEnd {
        LinkEnd {
            tx,
            sequence: Sequence::default(),
            refused,
        }
    }
}

/// What [`Links::deliver`] did with a message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Delivery {
    /// Queued for the connection's client.
    Forwarded,
    /// A duplicate, dropped; the connection goes on.
    Dropped,
    /// A gap, or a client too slow: the connection ended (its client
    /// reconnects).
    Ended,
    /// This node has no such connection (it closed, or its connect was
    /// given up as late): the owner should stop serving it.
    Unknown,
}

/// The relayed connections of this node's clients, by link.
#[derive(Default)]
pub(super) struct Links(HashMap<u64, LinkEnd>);

impl Links {
    pub fn insert(&mut self, link: u64, end: LinkEnd) {
        self.0.insert(link, end);
    }

    /// Removes `link`: dropping its sender ends its connection.
    pub fn remove(&mut self, link: &u64) -> Option<LinkEnd> {
        self.0.remove(link)
    }

    pub fn contains(&self, link: &u64) -> bool {
        self.0.contains_key(link)
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Ends every connection (the subscription they came through broke).
    pub fn clear(&mut self) {
        self.0.clear();
    }

    /// Hands message number `seq` (`text`) to connection `link`, and the
    /// owner's count of its refused messages (see the module's
    /// documentation).
    pub fn deliver(&mut self, link: u64, seq: u64, text: ByteString, refused: u32) -> Delivery {
        let Some(end) = self.0.get_mut(&link) else {
            return Delivery::Unknown;
        };
        end.refused.store(refused, Ordering::Relaxed);
        match end.sequence.order(seq) {
            Order::Duplicate => Delivery::Dropped,
            Order::Gap => {
                tracing::debug!(
                    link,
                    seq,
                    expected = end.sequence.expected(),
                    "a relayed connection ends"
                );
                self.0.remove(&link);
                Delivery::Ended
            }
            Order::Next => {
                let item: Outbound = Arc::from(vec![text]);
                if end.tx.try_send(item).is_err() {
                    tracing::debug!(link, seq, "a relayed connection too slow ends");
                    self.0.remove(&link);
                    return Delivery::Ended;
                }
                end.sequence.advance();
                Delivery::Forwarded
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table with connection 1, whose queue holds `room` messages.
    fn one_link(room: usize) -> (Links, mpsc::Receiver<Outbound>, Arc<AtomicU32>) {
        let (tx, rx) = mpsc::channel(room);
        let refused = Arc::new(AtomicU32::new(0));
        let mut links = Links::default();
        links.insert(1, LinkEnd::new(tx, refused.clone()));
        (links, rx, refused)
    }

    fn texts(rx: &mut mpsc::Receiver<Outbound>) -> Vec<String> {
        let mut out = Vec::new();
        while let Ok(item) = rx.try_recv() {
            out.extend(item.iter().map(|s| s.to_string()));
        }
        out
    }

    #[test]
    fn a_sequence_takes_numbers_in_order_and_tells_duplicates_from_gaps() {
        let mut s = Sequence::default();
        assert_eq!(s.order(0), Order::Next);
        s.advance();
        assert_eq!(s.order(0), Order::Duplicate);
        assert_eq!(s.order(1), Order::Next);
        assert_eq!(s.order(2), Order::Gap);
        assert_eq!(s.expected(), 1);
    }

    #[test]
    fn messages_in_order_are_forwarded_in_order() {
        let (mut links, mut rx, _) = one_link(8);
        for (seq, text) in ["a", "b", "c"].into_iter().enumerate() {
            let d = links.deliver(1, seq as u64, text.into(), 0);
            assert_eq!(d, Delivery::Forwarded);
        }
        assert_eq!(texts(&mut rx), ["a", "b", "c"]);
        assert!(links.contains(&1));
    }

    #[test]
    fn a_duplicate_is_dropped_and_the_connection_goes_on() {
        let (mut links, mut rx, _) = one_link(8);
        assert_eq!(links.deliver(1, 0, "a".into(), 0), Delivery::Forwarded);
        assert_eq!(links.deliver(1, 0, "a".into(), 0), Delivery::Dropped);
        assert_eq!(links.deliver(1, 1, "b".into(), 0), Delivery::Forwarded);
        assert_eq!(texts(&mut rx), ["a", "b"]);
    }

    #[test]
    fn a_gap_ends_the_connection_and_nothing_after_it_is_forwarded() {
        let (mut links, mut rx, _) = one_link(8);
        assert_eq!(links.deliver(1, 0, "a".into(), 0), Delivery::Forwarded);
        assert_eq!(links.deliver(1, 2, "c".into(), 0), Delivery::Ended);
        assert!(!links.contains(&1));
        assert_eq!(links.deliver(1, 1, "b".into(), 0), Delivery::Unknown);
        assert_eq!(texts(&mut rx), ["a"]);
        // The sender went with the link: the client's queue ends.
        assert!(rx.try_recv().is_err() && rx.is_closed());
    }

    #[test]
    fn a_client_too_slow_for_one_more_message_is_dropped() {
        let (mut links, mut rx, _) = one_link(2);
        assert_eq!(links.deliver(1, 0, "a".into(), 0), Delivery::Forwarded);
        assert_eq!(links.deliver(1, 1, "b".into(), 0), Delivery::Forwarded);
        assert_eq!(links.deliver(1, 2, "c".into(), 0), Delivery::Ended);
        assert_eq!(links.len(), 0);
        assert_eq!(texts(&mut rx), ["a", "b"]);
    }

    #[test]
    fn a_message_for_a_connection_this_node_does_not_have_is_unknown() {
        let (mut links, _rx, _) = one_link(2);
        assert_eq!(links.deliver(9, 0, "a".into(), 0), Delivery::Unknown);
        assert!(links.contains(&1));
    }

    #[test]
    fn the_owners_count_of_refused_messages_is_kept_even_from_a_duplicate() {
        let (mut links, _rx, refused) = one_link(8);
        links.deliver(1, 0, "a".into(), 1);
        assert_eq!(refused.load(Ordering::Relaxed), 1);
        links.deliver(1, 0, "a".into(), 3);
        assert_eq!(refused.load(Ordering::Relaxed), 3);
    }
}
