//! Where frames travel: a small transport interface, and an in-process bus for tests and emulators
//! (every frame one endpoint sends reaches every other endpoint, in order, as on a CAN bus).
//! A lab's transport (SocketCAN on Linux) implements the same trait.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

use super::frame::CanFrame;

/// A transport failed (the interface went down, the bus is gone).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("CAN transport: {0}")]
pub struct TransportError(pub String);

/// Sends and receives CAN frames.
pub trait CanTransport: Send {
    /// Sends one frame.
    fn send(&mut self, frame: &CanFrame) -> Result<(), TransportError>;
    /// The next frame received, without waiting (None: none has come).
    fn try_recv(&mut self) -> Result<Option<CanFrame>, TransportError>;
}

/// An in-process CAN bus.
#[derive(Clone, Default)]
pub struct MemoryBus {
    queues: Arc<Mutex<Vec<VecDeque<CanFrame>>>>,
}

/// One participant of a [`MemoryBus`].
pub struct MemoryEndpoint {
    bus: MemoryBus,
    index: usize,
}

impl MemoryBus {
    /// An empty bus.
    pub fn new() -> Self {
        Self::default()
    }

    /// A new participant.
    pub fn endpoint(&self) -> MemoryEndpoint {
        let mut queues = self.queues.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        queues.push(VecDeque::new());
        MemoryEndpoint { bus: self.clone(), index: queues.len() - 1 }
    }
}

/// Frames waiting at one participant beyond which the oldest are dropped (a receive buffer's
/// overflow; a participant that never reads must not grow without bound).
const QUEUE_LIMIT: usize = 4096;

impl CanTransport for MemoryEndpoint {
    fn send(&mut self, frame: &CanFrame) -> Result<(), TransportError> {
        let mut queues =
            self.bus.queues.lock().map_err(|_| TransportError("the bus's lock is poisoned".into()))?;
        for (k, queue) in queues.iter_mut().enumerate() {
            if k != self.index {
                if queue.len() >= QUEUE_LIMIT {
                    queue.pop_front();
                }
                queue.push_back(*frame);
            }
        }
        Ok(())
    }

    fn try_recv(&mut self) -> Result<Option<CanFrame>, TransportError> {
        let mut queues =
            self.bus.queues.lock().map_err(|_| TransportError("the bus's lock is poisoned".into()))?;
        Ok(queues[self.index].pop_front())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame reaches every other participant, in order, and not its sender.
    #[test]
    fn a_frame_reaches_every_other_participant() {
        let bus = MemoryBus::new();
        let (mut a, mut b, mut c) = (bus.endpoint(), bus.endpoint(), bus.endpoint());
        let f = |id| CanFrame::new(id, &[1]).expect("a frame");
        a.send(&f(1)).expect("sent");
        a.send(&f(2)).expect("sent");
        assert_eq!(a.try_recv(), Ok(None));
        for endpoint in [&mut b, &mut c] {
            assert_eq!(endpoint.try_recv(), Ok(Some(f(1))));
            assert_eq!(endpoint.try_recv(), Ok(Some(f(2))));
            assert_eq!(endpoint.try_recv(), Ok(None));
        }
    }
}
