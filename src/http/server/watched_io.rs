//! The socket of one connection, watched: each read or write that has to wait checks the
//! connection's deadline, and fails with `TimedOut` once it has passed, which ends the
//! connection (hyper closes it; a request body being read sees the error, and the service
//! answers 408).
//!
//! hyper 1.x has only a header read timeout (`http1::Builder::header_read_timeout`), and its
//! timer starts when the connection begins to wait for a head — on a kept-alive connection,
//! right after the previous response — so it cannot tell a short head timeout from a long
//! idle timeout, and it has no body or send timeout at all. This wrapper keeps one timer per
//! connection for all of them; the deadline depends on the connection's phase
//! ([`super::connection`]): an idle connection gets the idle timeout, and its next request's
//! head the header timeout from its first byte.

use std::io;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::Duration;

use pin_project_lite::pin_project;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::time::{Instant, Sleep};

use super::connection::{Connection, Phase};
use crate::config::ConnectionLimits;
use crate::http::metrics::CloseReason;
use crate::http::state::Readiness;

/// While draining, how long an idle connection is kept for a request that is about to come
/// (it is answered 503 with `Connection: close`); closing at once could cut a request the
/// client was sending just then.
pub(super) const DRAIN_IDLE_GRACE: Duration = Duration::from_secs(1);

/// The timeouts a watched socket applies.
#[derive(Debug, Clone, Copy)]
pub(super) struct Timeouts {
    pub(super) header: Duration,
    pub(super) idle: Duration,
    pub(super) body: Duration,
}

impl From<ConnectionLimits> for Timeouts {
    fn from(limits: ConnectionLimits) -> Timeouts {
        Timeouts {
            header: limits.header_timeout(),
            idle: limits.idle_timeout(),
            body: limits.body_timeout(),
        }
    }
}

pin_project! {
    /// A socket whose waits are bounded by the connection's deadlines.
    pub(super) struct WatchedIo<T> {
        #[pin]
        io: T,
        connection: Arc<Connection>,
        timeouts: Timeouts,
        readiness: Readiness,
        // One timer for every deadline; it is moved earlier when needed and, when it fires
        // for a deadline that has since moved later, re-armed (so a kept-alive connection does
        // not touch the timer on every request).
        timer: Pin<Box<Sleep>>,
        armed: Instant,
        // A read is waiting for bytes.
        read_waiting: bool,
        // Since when writes have made no progress.
        write_stalled_since: Option<Instant>,
    }
}

impl<T> WatchedIo<T> {
    /// Watches `io`, accepted at `accepted`.
    pub(super) fn new(
        io: T,
        connection: Arc<Connection>,
        timeouts: Timeouts,
        readiness: Readiness,
        accepted: Instant,
    ) -> Self {
        let armed = accepted + timeouts.header;
        WatchedIo {
            io,
            connection,
            timeouts,
            readiness,
            timer: Box::pin(tokio::time::sleep_until(armed)),
            armed,
            read_waiting: false,
            write_stalled_since: None,
        }
    }
}

/// The deadline a waiting read has in the connection's current phase, and the reason to
/// record when it passes. While a request is handled there is none (the request timeout
/// bounds it), only a time to check back (reason `None`): hyper does not read again after
/// the response, so the idle deadline that follows is found when the task next wakes.
fn read_deadline(
    connection: &Connection,
    timeouts: &Timeouts,
    draining: bool,
) -> (Instant, Option<CloseReason>) {
    let since = connection.since();
    match connection.phase() {
        Phase::Head => (since + timeouts.header, Some(CloseReason::HeaderTimeout)),
        Phase::Body => (since + timeouts.body, Some(CloseReason::BodyTimeout)),
        Phase::Handling => (since + timeouts.idle, None),
        Phase::Idle if draining => (
            since + timeouts.idle.min(DRAIN_IDLE_GRACE),
            Some(CloseReason::Shutdown),
        ),
        Phase::Idle => (since + timeouts.idle, Some(CloseReason::IdleTimeout)),
        Phase::Evicted => (since, Some(CloseReason::Evicted)),
    }
}

impl<T> WatchedIo<T> {
    /// Fails the connection if it was evicted.
    fn check_evicted(connection: &Connection) -> io::Result<()> {
        if connection.phase() == Phase::Evicted {
            Err(io::Error::new(
                io::ErrorKind::ConnectionAborted,
                "evicted at the connection cap",
            ))
        } else {
            Ok(())
        }
    }
}

/// The earliest deadline of a waiting read and a stalled write, and its reason.
fn earliest_deadline(
    connection: &Connection,
    timeouts: &Timeouts,
    readiness: &Readiness,
    read_waiting: bool,
    write_stalled_since: Option<Instant>,
) -> Option<(Instant, Option<CloseReason>)> {
    let read = read_waiting.then(|| read_deadline(connection, timeouts, !readiness.is_ready()));
    let write =
        write_stalled_since.map(|since| (since + timeouts.body, Some(CloseReason::SendTimeout)));
    match (read, write) {
        (Some(read), Some(write)) => Some(if write.0 < read.0 { write } else { read }),
        (read, write) => read.or(write),
    }
}

impl<T> WatchedIo<T> {
    /// After an operation had to wait: `Err(TimedOut)` if the earliest deadline has passed,
    /// otherwise arms the timer so that the task wakes at that deadline.
    fn poll_deadline(self: Pin<&mut Self>, cx: &mut Context<'_>) -> io::Result<()> {
        let this = self.project();
        let Some((mut deadline, reason)) = earliest_deadline(
            this.connection,
            this.timeouts,
            this.readiness,
            *this.read_waiting,
            *this.write_stalled_since,
        ) else {
            return Ok(());
        };
        loop {
            if deadline < *this.armed || this.timer.is_elapsed() {
                this.timer.as_mut().reset(deadline);
                *this.armed = deadline;
            }
            if this.timer.as_mut().poll(cx).is_pending() {
                return Ok(());
            }
            let now = Instant::now();
            if now < deadline {
                // It fired for an earlier deadline that has since moved later.
                continue;
            }
            match reason {
                Some(reason) => {
                    this.connection.record_close_reason(reason);
                    return Err(io::Error::new(io::ErrorKind::TimedOut, reason.label()));
                }
                // A time to check back that has passed: check back later.
                None => deadline = now + this.timeouts.idle,
            }
        }
    }

    /// Notes the outcome of a write: progress clears a stall, waiting starts one.
    fn note_write<R>(self: Pin<&mut Self>, poll: &Poll<io::Result<R>>) {
        let this = self.project();
        if poll.is_pending() {
            if this.write_stalled_since.is_none() {
                *this.write_stalled_since = Some(Instant::now());
                this.connection.set_write_stalled(true);
            }
        } else if this.write_stalled_since.take().is_some() {
            this.connection.set_write_stalled(false);
        }
    }

    /// The result of a write that had to wait: pending, or failed past a deadline.
    fn poll_after_write<R>(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        poll: Poll<io::Result<R>>,
    ) -> Poll<io::Result<R>> {
        self.as_mut().note_write(&poll);
        if poll.is_pending() {
            self.poll_deadline(cx)?;
        }
        poll
    }
}

impl<T: AsyncRead> AsyncRead for WatchedIo<T> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Self::check_evicted(&self.connection)?;
        let this = self.as_mut().project();
        let before = buf.filled().len();
        match this.io.poll_read(cx, buf) {
            Poll::Ready(result) => {
                *this.read_waiting = false;
                if buf.filled().len() > before {
                    this.connection.bytes_received();
                }
                Poll::Ready(result)
            }
            Poll::Pending => {
                *this.read_waiting = true;
                self.poll_deadline(cx)?;
                Poll::Pending
            }
        }
    }
}

impl<T: AsyncWrite> AsyncWrite for WatchedIo<T> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        Self::check_evicted(&self.connection)?;
        let poll = self.as_mut().project().io.poll_write(cx, buf);
        self.poll_after_write(cx, poll)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        Self::check_evicted(&self.connection)?;
        let poll = self.as_mut().project().io.poll_write_vectored(cx, bufs);
        self.poll_after_write(cx, poll)
    }

    fn is_write_vectored(&self) -> bool {
        self.io.is_write_vectored()
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let poll = self.as_mut().project().io.poll_flush(cx);
        self.poll_after_write(cx, poll)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        self.project().io.poll_shutdown(cx)
    }
}
