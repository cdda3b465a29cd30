//! One connection's state, shared by its socket watchdog ([`super::watched_io::WatchedIo`]),
//! its request service ([`super::service::ConnectionService`]) and the accept loop, which may
//! evict it: the phase the connection is in and since when, and why it ended.
//!
//! Phases of an HTTP/1 connection, and the deadline each one sets for reading:
//!
//! | phase      | from                                          | deadline              |
//! |------------|-----------------------------------------------|-----------------------|
//! | `Head`     | accept, or the first byte of the next request | header timeout        |
//! | `Body`     | the head is complete (service called)         | body timeout          |
//! | `Handling` | the body is complete                          | none (request timeout)|
//! | `Idle`     | the response is complete                      | idle timeout          |
//! | `Evicted`  | displaced at the connection cap               | now                   |

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicU64, Ordering};

use tokio::sync::Notify;
use tokio::time::Instant;

use crate::http::metrics::CloseReason;

/// Where a connection is in its request/response cycle (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Phase {
    /// Waiting for (the rest of) a request head.
    Head = 0,
    /// Receiving a request body.
    Body = 1,
    /// Computing or sending the response.
    Handling = 2,
    /// Between requests.
    Idle = 3,
    /// Displaced at the cap; the socket fails its next read or write.
    Evicted = 4,
}

impl Phase {
    fn from_u8(value: u8) -> Phase {
        match value {
            0 => Phase::Head,
            1 => Phase::Body,
            2 => Phase::Handling,
            3 => Phase::Idle,
            _ => Phase::Evicted,
        }
    }
}

/// The shared state of one connection.
#[derive(Debug)]
pub(super) struct Connection {
    /// Position in accept order (the registry's key).
    pub(super) id: u64,
    /// The instant `since_nanos` counts from (shared by all connections of a server).
    epoch: Instant,
    phase: AtomicU8,
    /// When the current phase began, in nanoseconds after `epoch`.
    since_nanos: AtomicU64,
    /// `CloseReason::ALL` index + 1 of the reason recorded first; 0: none yet.
    close_reason: AtomicU8,
    /// Set when a request arrived just as the connection was evicted: it is served, with
    /// `Connection: close`.
    close_after_response: AtomicBool,
    /// The socket refuses more response bytes (the client does not read).
    write_stalled: AtomicBool,
    /// Wakes the connection's task (eviction, draining), so that its socket checks its state.
    wake: Notify,
}

impl Connection {
    /// A connection accepted at `now`, waiting for its first request head.
    pub(super) fn new(id: u64, epoch: Instant, now: Instant) -> Arc<Connection> {
        Arc::new(Connection {
            id,
            epoch,
            phase: AtomicU8::new(Phase::Head as u8),
            since_nanos: AtomicU64::new(nanos_between(epoch, now)),
            close_reason: AtomicU8::new(0),
            close_after_response: AtomicBool::new(false),
            write_stalled: AtomicBool::new(false),
            wake: Notify::new(),
        })
    }

    /// The current phase.
    pub(super) fn phase(&self) -> Phase {
        Phase::from_u8(self.phase.load(Ordering::Acquire))
    }

    /// When the current phase began.
    pub(super) fn since(&self) -> Instant {
        self.epoch + std::time::Duration::from_nanos(self.since_nanos.load(Ordering::Relaxed))
    }

    /// Moves `from` → `to` (at `now`) if the connection is in `from`.
    fn transition(&self, from: Phase, to: Phase, now: Instant) -> bool {
        let moved = self
            .phase
            .compare_exchange(from as u8, to as u8, Ordering::AcqRel, Ordering::Acquire)
            .is_ok();
        if moved {
            self.since_nanos
                .store(nanos_between(self.epoch, now), Ordering::Relaxed);
        }
        moved
    }

    /// Bytes arrived: an idle connection starts receiving a request head.
    pub(super) fn bytes_received(&self) {
        if self.phase() == Phase::Idle {
            self.transition(Phase::Idle, Phase::Head, Instant::now());
        }
    }

    /// A request head is complete; `body_complete` when it has no body to wait for. A request
    /// that raced with an eviction wins, and the connection closes after its response.
    pub(super) fn request_started(&self, body_complete: bool) {
        let phase = if body_complete {
            Phase::Handling
        } else {
            Phase::Body
        };
        let before = self.phase.swap(phase as u8, Ordering::AcqRel);
        self.since_nanos
            .store(nanos_between(self.epoch, Instant::now()), Ordering::Relaxed);
        if Phase::from_u8(before) == Phase::Evicted {
            self.close_after_response.store(true, Ordering::Relaxed);
        }
    }

    /// The request body has been received whole.
    pub(super) fn body_finished(&self) {
        self.transition(Phase::Body, Phase::Handling, Instant::now());
    }

    /// The response has been handed to the socket whole (or abandoned).
    pub(super) fn response_finished(&self) {
        let now = Instant::now();
        if !self.transition(Phase::Handling, Phase::Idle, now) {
            self.transition(Phase::Body, Phase::Idle, now);
        }
    }

    /// Whether the response must say `Connection: close` because of a raced eviction.
    pub(super) fn close_after_response(&self) -> bool {
        self.close_after_response.load(Ordering::Relaxed)
    }

    /// Marks whether the socket currently refuses response bytes.
    pub(super) fn set_write_stalled(&self, stalled: bool) {
        if self.write_stalled.load(Ordering::Relaxed) != stalled {
            self.write_stalled.store(stalled, Ordering::Relaxed);
        }
    }

    /// Whether the connection may be displaced: it is waiting for a request (idle, or a head
    /// that is not complete), or its client does not read its response.
    pub(super) fn is_evictable(&self) -> bool {
        match self.phase() {
            Phase::Head | Phase::Idle => true,
            Phase::Handling => self.write_stalled.load(Ordering::Relaxed),
            Phase::Body | Phase::Evicted => false,
        }
    }

    /// Evicts the connection if it is still evictable; true when it was.
    pub(super) fn try_evict(&self) -> bool {
        let phase = self.phase();
        let evictable = match phase {
            Phase::Head | Phase::Idle => true,
            Phase::Handling => self.write_stalled.load(Ordering::Relaxed),
            Phase::Body | Phase::Evicted => false,
        };
        if evictable && self.transition(phase, Phase::Evicted, Instant::now()) {
            self.record_close_reason(CloseReason::Evicted);
            self.wake();
            true
        } else {
            false
        }
    }

    /// Records why the connection is about to end; the first reason recorded stays.
    pub(super) fn record_close_reason(&self, reason: CloseReason) {
        let code = CloseReason::ALL
            .iter()
            .position(|r| *r == reason)
            .map_or(0, |index| index as u8 + 1);
        let _ = self
            .close_reason
            .compare_exchange(0, code, Ordering::AcqRel, Ordering::Acquire);
    }

    /// The reason recorded, if any.
    pub(super) fn close_reason(&self) -> Option<CloseReason> {
        let code = self.close_reason.load(Ordering::Acquire);
        CloseReason::ALL
            .get(usize::from(code).checked_sub(1)?)
            .copied()
    }

    /// Wakes the connection's task so that its socket re-checks the state.
    pub(super) fn wake(&self) {
        self.wake.notify_one();
    }

    /// Completes when [`Connection::wake`] is called (or was, since the last wait).
    pub(super) async fn woken(&self) {
        self.wake.notified().await;
    }
}

fn nanos_between(epoch: Instant, now: Instant) -> u64 {
    u64::try_from(now.saturating_duration_since(epoch).as_nanos()).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_phases_follow_a_request_and_eviction_spares_busy_connections() {
        let now = Instant::now();
        let connection = Connection::new(1, now, now);
        assert_eq!(connection.phase(), Phase::Head);
        assert!(connection.is_evictable());
        connection.request_started(false);
        assert_eq!(connection.phase(), Phase::Body);
        assert!(
            !connection.try_evict(),
            "a body on its way is not displaced"
        );
        connection.body_finished();
        assert_eq!(connection.phase(), Phase::Handling);
        assert!(
            !connection.try_evict(),
            "a request being served is not displaced"
        );
        connection.set_write_stalled(true);
        assert!(connection.is_evictable(), "a client that does not read is");
        connection.set_write_stalled(false);
        connection.response_finished();
        assert_eq!(connection.phase(), Phase::Idle);
        connection.bytes_received();
        assert_eq!(connection.phase(), Phase::Head);
        assert!(connection.try_evict());
        assert_eq!(connection.phase(), Phase::Evicted);
        assert_eq!(connection.close_reason(), Some(CloseReason::Evicted));
        connection.record_close_reason(CloseReason::Error);
        assert_eq!(connection.close_reason(), Some(CloseReason::Evicted));
    }

    #[test]
    fn a_request_that_races_an_eviction_is_served_then_the_connection_closes() {
        let now = Instant::now();
        let connection = Connection::new(1, now, now);
        assert!(connection.try_evict());
        connection.request_started(true);
        assert_eq!(connection.phase(), Phase::Handling);
        assert!(connection.close_after_response());
        connection.response_finished();
        assert_eq!(connection.phase(), Phase::Idle);
    }
}
