//! The owner's way back to another node: what its rooms send the
//! connections it serves for that node's clients leaves in one stream per
//! node, not one per connection. An outlet (a task per node, which
//! [`super::serve`] runs) takes whatever those connections' queues hold at
//! the moment, numbers each message per
//! connection from 0 (the numbering [`super::relay`] checks on the other
//! side), and publishes it all as one [`Envelope::Deliveries`]: each
//! distinct message once (a broadcast the room shares among its
//! connections is encoded and carried once, however many of that node's
//! clients watch the match), with the list of (connection, number,
//! message) that the other node fans out to its clients. A connection
//! whose queue ended (the room closed it) is listed as closed after its
//! last message. An outlet with no connection left ends; the next
//! connection served for its node starts another.

use super::wire::{Addressed, Envelope};
use crate::play::room::Inbox;
use bytestring::ByteString;
use futures_util::stream::{self, BoxStream, SelectAll};
use futures_util::{FutureExt, StreamExt};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

/// Most messages one envelope carries.
const MAX_BATCH: usize = 256;

/// A served connection, handed to the outlet of its client's node.
pub(super) struct Outgoing {
    /// The connection's number on its client's node.
    pub link: u64,
    /// What the room sends it.
    pub rx: Inbox,
    /// How many of its messages the room refused.
    pub refused: Arc<AtomicU32>,
}

/// What one connection's queue yields.
#[derive(Debug)]
pub(super) enum Event {
    /// A message for connection `link`, and its count of refused messages.
    Message(u64, ByteString, u32),
    /// The room closed connection `link`: nothing follows.
    Closed(u64),
}

/// The events of one connection: its messages, then [`Event::Closed`].
pub(super) fn events(o: Outgoing) -> BoxStream<'static, Event> {
    stream::unfold(Some(o), |state| async move {
        let mut o = state?;
        match o.rx.recv().await {
            Some(text) => {
                let event = Event::Message(o.link, text, o.refused.load(Ordering::Relaxed));
                Some((event, Some(o)))
            }
            None => Some((Event::Closed(o.link), None)),
        }
    })
    .boxed()
}

/// The next events of `streams`: the first to come, and every other one
/// ready at that moment (at most [`MAX_BATCH`]). Empty once every stream
/// has ended.
pub(super) async fn next_batch(streams: &mut SelectAll<BoxStream<'static, Event>>) -> Vec<Event> {
    let Some(first) = streams.next().await else {
        return Vec::new();
    };
    let mut batch = vec![first];
    while batch.len() < MAX_BATCH {
        match streams.next().now_or_never() {
            Some(Some(e)) => batch.push(e),
            _ => break,
        }
    }
    batch
}

/// The envelope carrying `batch` from node `from`: each message once (the
/// same message shared by several connections is one text, told apart by
/// its storage, not compared), numbered per connection after the numbers
/// in `seqs`, which it moves on (and forgets the closed connections).
pub(super) fn envelope(from: &str, batch: Vec<Event>, seqs: &mut HashMap<u64, u64>) -> Envelope {
    let mut texts: Vec<String> = Vec::new();
    let mut index: HashMap<(usize, usize), usize> = HashMap::new();
    let mut to = Vec::with_capacity(batch.len());
    let mut closed = Vec::new();
    for e in batch {
        match e {
            Event::Message(link, text, refused) => {
                let key = (text.as_ptr() as usize, text.len());
                let text = *index.entry(key).or_insert_with(|| {
                    texts.push(text.to_string());
                    texts.len() - 1
                });
                let seq = seqs.entry(link).or_insert(0);
                to.push(Addressed {
                    link,
                    seq: *seq,
                    text,
                    refused,
                });
                *seq += 1;
            }
            Event::Closed(link) => {
                seqs.remove(&link);
                closed.push(link);
            }
        }
    }
    Envelope::Deliveries {
        from: from.to_string(),
        texts,
        to,
        closed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::play::room::Outbound;
    use tokio::sync::mpsc;

    /// A served connection `link` and the room's end of its queue.
    fn served(link: u64) -> (mpsc::Sender<Outbound>, Outgoing) {
        let (tx, rx) = mpsc::channel(8);
        let o = Outgoing {
            link,
            rx: Inbox::new(rx),
            refused: Arc::new(AtomicU32::new(0)),
        };
        (tx, o)
    }

    fn item(texts: &[ByteString]) -> Outbound {
        Arc::from(texts.to_vec())
    }

    #[tokio::test]
    async fn a_message_shared_by_several_connections_crosses_once_numbered_for_each() {
        let (tx1, o1) = served(1);
        let (tx2, o2) = served(2);
        let mut streams = SelectAll::new();
        streams.push(events(o1));
        streams.push(events(o2));
        let shot = ByteString::from(r#"{"type":"shot-played"}"#);
        let clock = ByteString::from(r#"{"type":"clock"}"#);
        let everyone = item(&[shot.clone(), clock.clone()]);
        tx1.send(everyone.clone()).await.unwrap();
        tx2.send(everyone).await.unwrap();
        // Only connection 2 is told this one.
        tx2.send(item(&[ByteString::from(r#"{"type":"error"}"#)]))
            .await
            .unwrap();
        let mut seqs = HashMap::new();
        let batch = next_batch(&mut streams).await;
        assert_eq!(batch.len(), 5);
        let Envelope::Deliveries {
            texts, to, closed, ..
        } = envelope("a", batch, &mut seqs)
        else {
            unreachable!()
        };
        assert_eq!(texts.len(), 3, "{texts:?}");
        assert!(closed.is_empty());
        let of = |link: u64| -> Vec<(u64, &str)> {
            to.iter()
                .filter(|a| a.link == link)
                .map(|a| (a.seq, texts[a.text].as_str()))
                .collect()
        };
        assert_eq!(of(1), [(0, &*shot), (1, &*clock)]);
        assert_eq!(
            of(2),
            [(0, &*shot), (1, &*clock), (2, r#"{"type":"error"}"#)]
        );
    }

    #[tokio::test]
    async fn numbers_go_on_across_envelopes_and_a_closed_connection_comes_after_its_last_message() {
        let (tx, o) = served(7);
        let mut streams = SelectAll::new();
        streams.push(events(o));
        let mut seqs = HashMap::new();
        tx.send(item(&["a".into()])).await.unwrap();
        let first = envelope("a", next_batch(&mut streams).await, &mut seqs);
        tx.send(item(&["b".into()])).await.unwrap();
        drop(tx);
        let second = envelope("a", next_batch(&mut streams).await, &mut seqs);
        let Envelope::Deliveries { to, .. } = first else {
            unreachable!()
        };
        assert_eq!((to[0].link, to[0].seq), (7, 0));
        let Envelope::Deliveries {
            texts, to, closed, ..
        } = second
        else {
            unreachable!()
        };
        assert_eq!((to[0].seq, texts[to[0].text].as_str()), (1, "b"));
        assert_eq!(closed, [7]);
        assert!(seqs.is_empty(), "a closed connection's number is forgotten");
        assert!(next_batch(&mut streams).await.is_empty());
    }
}
