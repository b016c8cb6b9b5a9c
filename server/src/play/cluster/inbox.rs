//! A node's inbox: its Redis channel, read for good, and what it does with
//! each [`Envelope`] another node sent it: as the owner of a match, it
//! starts serving relayed connections ([`super::serve`]) and hands their
//! messages and joins to its rooms; as the node of a client, it settles
//! pending connects and joins and fans each envelope of deliveries out to
//! its connections, each in order ([`super::relay`]).

use super::node::{lock, Cluster};
use super::relay::Delivery;
use super::rooms::LocalRooms;
use super::serve::serve;
use super::wire::{channel, Envelope, WireRefusal};
use crate::play::room::Command;
use crate::refusal::Refusal;
use bytestring::ByteString;
use futures_util::StreamExt;
use game::protocol::{ClientMessage, ErrorCode};
use game::token::TokenHash;
use std::sync::Arc;
use std::time::Duration;
use tracing::{debug, warn};

/// Reads this node's channel for good (subscribing again after Redis
/// breaks; the connections relayed meanwhile end, since their messages
/// may be lost) and handles each envelope.
pub(super) async fn dispatch<R: LocalRooms>(cluster: Arc<Cluster>, rooms: R) {
    loop {
        match cluster.redis.get_async_pubsub().await {
            Ok(mut pubsub) => {
                if let Err(e) = pubsub.subscribe(channel(&cluster.node)).await {
                    warn!(error = %e, "subscribing to this node's channel failed");
                } else {
                    let mut messages = pubsub.on_message();
                    while let Some(m) = messages.next().await {
                        let Ok(text) = m.get_payload::<String>() else {
                            continue;
                        };
                        match Envelope::decode(&text) {
                            Ok(e) => handle(&cluster, &rooms, e).await,
                            Err(e) => warn!(error = %e, "an unreadable message from another node"),
                        }
                    }
                    warn!("this node's Redis subscription ended; subscribing again");
                }
            }
            Err(e) => warn!(error = %e, "cannot reach Redis; trying again"),
        }
        lock(&cluster.links).clear();
        tokio::time::sleep(Duration::from_secs(1)).await;
    }
}

async fn handle<R: LocalRooms>(cluster: &Arc<Cluster>, rooms: &R, e: Envelope) {
    match e {
        Envelope::Connect {
            from,
            link,
            match_id,
            claim,
        } => {
            let (cluster, rooms) = (cluster.clone(), rooms.clone());
            tokio::spawn(serve(cluster, rooms, from, link, match_id, claim.into()));
        }
        Envelope::Message { from, link, text } => {
            let target = lock(&cluster.served)
                .get(&(from, link))
                .map(|s| (s.room.clone(), s.conn));
            if let (Some((room, conn)), Ok(msg)) = (target, ClientMessage::from_json(&text)) {
                let _ = room.send(Command::message(conn, msg)).await;
            }
        }
        Envelope::Disconnect { from, link } => {
            let served = lock(&cluster.served).remove(&(from, link));
            if let Some(s) = served {
                let _ = s.room.send(Command::Disconnect { conn: s.conn }).await;
            }
        }
        Envelope::Join {
            from,
            request,
            match_id,
            name,
            token,
            account,
        } => {
            let (cluster, rooms) = (cluster.clone(), rooms.clone());
            tokio::spawn(async move {
                let result = match TokenHash::from_hex(&token) {
                    Ok(token) => rooms.join_owned(&match_id, name, token, account).await,
                    Err(_) => Err(Refusal::new(ErrorCode::BadToken, "a malformed token hash")),
                };
                let result = result.map_err(|r| WireRefusal::from(&r));
                cluster
                    .send(&from, &Envelope::Joined { request, result })
                    .await;
            });
        }
        Envelope::Connected { link, conn, seat } => {
            let pending = lock(&cluster.pending_connects).remove(&link);
            if let Some(p) = pending {
                // In place before the first delivery is read.
                lock(&cluster.links).insert(link, p.end);
                let _ = p.reply.send(Ok(seat));
            }
            debug!(link, conn, "a relayed connection was admitted");
        }
        Envelope::Refused { link, refusal } => {
            if let Some(p) = lock(&cluster.pending_connects).remove(&link) {
                let _ = p.reply.send(Err(refusal.into()));
            }
        }
        Envelope::Deliveries {
            from,
            texts,
            to,
            closed,
        } => {
            let texts: Vec<ByteString> = texts.into_iter().map(ByteString::from).collect();
            let mut unknown: Vec<u64> = Vec::new();
            {
                let mut links = lock(&cluster.links);
                for a in to {
                    let Some(text) = texts.get(a.text) else {
                        // No such text: the connection misses a message.
                        warn!(link = a.link, "a delivery names a text its envelope lacks");
                        links.remove(&a.link);
                        continue;
                    };
                    let delivery = links.deliver(a.link, a.seq, text.clone(), a.refused);
                    if delivery == Delivery::Unknown && !unknown.contains(&a.link) {
                        unknown.push(a.link);
                    }
                }
                for link in closed {
                    links.remove(&link);
                }
            }
            // Connections this node no longer has (closed, or their connect
            // given up as late): the owner stops serving them.
            for link in unknown {
                let node = cluster.node.clone();
                cluster
                    .send(&from, &Envelope::Disconnect { from: node, link })
                    .await;
            }
        }
        Envelope::Joined { request, result } => {
            if let Some(tx) = lock(&cluster.pending_joins).remove(&request) {
                let _ = tx.send(result.map_err(Refusal::from));
            }
        }
    }
}
