//! The open connections of a server and the cap on their number. At the cap, a new
//! connection displaces the open one that has waited longest without a request in progress
//! (idle, a head not yet complete, or a response its client does not read); when every
//! connection is serving a request, the new one is refused at once.
//!
//! Requests in progress hold at most about the concurrency limit's worth of connections for
//! long (other `/v1` requests are shed with 503 at once, probes answer at once), and the cap
//! is never below that limit + [`crate::config::ConnectionLimits::PROBE_HEADROOM`]; so a
//! probe (`/healthz`, `/readyz`, `/metrics`) always finds a connection to displace, however
//! many idle or half-open connections clients hold.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

use tokio::time::Instant;

use super::connection::Connection;

/// The open connections.
#[derive(Debug)]
pub(super) struct Registry {
    epoch: Instant,
    cap: usize,
    open: Mutex<Open>,
}

#[derive(Debug, Default)]
struct Open {
    next_id: u64,
    connections: HashMap<u64, Arc<Connection>>,
}

/// A connection's place in the registry; dropping it frees the place.
#[derive(Debug)]
pub(super) struct Registered {
    pub(super) connection: Arc<Connection>,
    registry: Arc<Registry>,
}

impl Drop for Registered {
    fn drop(&mut self) {
        self.registry.lock().connections.remove(&self.connection.id);
    }
}

impl Registry {
    /// An empty registry allowing `cap` connections (at least one).
    pub(super) fn new(cap: usize) -> Arc<Registry> {
        Arc::new(Registry {
            epoch: Instant::now(),
            cap: cap.max(1),
            open: Mutex::new(Open::default()),
        })
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Open> {
        // The map stays consistent whatever panicked while holding the lock.
        self.open.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Registers a connection accepted at `now`, displacing one at the cap; `None` when the
    /// cap is reached and no connection can be displaced. A displaced connection closes
    /// within microseconds, so the number open may pass the cap by the few closing then.
    pub(super) fn admit(self: &Arc<Self>, now: Instant) -> Option<Registered> {
        let mut open = self.lock();
        if open.connections.len() >= self.cap && !Self::evict_longest_waiting(&open) {
            return None;
        }
        open.next_id += 1;
        let connection = Connection::new(open.next_id, self.epoch, now);
        open.connections.insert(connection.id, connection.clone());
        Some(Registered {
            connection,
            registry: self.clone(),
        })
    }

    /// Evicts the evictable connection whose current wait began earliest; false when none
    /// could be evicted.
    fn evict_longest_waiting(open: &Open) -> bool {
        // A connection may start a request between the choice and the eviction; then try the
        // next one (a few tries: each loss is a request that just started).
        for _ in 0..4 {
            let candidate = open
                .connections
                .values()
                .filter(|connection| connection.is_evictable())
                .min_by_key(|connection| connection.since());
            match candidate {
                None => return false,
                Some(connection) if connection.try_evict() => return true,
                Some(_) => {}
            }
        }
        false
    }

    /// Wakes every open connection (draining has begun: idle ones close, the others answer
    /// with `Connection: close`).
    pub(super) fn wake_all(&self) {
        for connection in self.lock().connections.values() {
            connection.wake();
        }
    }

    /// The number of connections registered.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.lock().connections.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::http::server::connection::Phase;

    #[test]
    fn at_the_cap_the_longest_waiting_idle_connection_makes_room() {
        let registry = Registry::new(2);
        let t0 = Instant::now();
        let first = registry.admit(t0).unwrap();
        let second = registry
            .admit(t0 + std::time::Duration::from_millis(5))
            .unwrap();
        // The first serves a request; the second waits for its head.
        first.connection.request_started(true);
        let third = registry.admit(t0).expect("the waiting one is displaced");
        assert_eq!(second.connection.phase(), Phase::Evicted);
        assert_eq!(first.connection.phase(), Phase::Handling);
        drop(second);
        assert_eq!(registry.len(), 2);
        // Both open connections now serve requests: the next one is refused.
        third.connection.request_started(false);
        assert!(registry.admit(t0).is_none());
        drop(first);
        assert!(registry.admit(t0).is_some(), "a freed place is taken");
    }
}
