//! Asynchronous operations of the HAL (`init`, `manipulate`, `movemode`): each
//! takes a plausible time on the robot side and its outcome is decided when
//! it completes, from the simulator's state at that moment.

use ilmr_hal::{AsyncOp, ManipTask, OpId, OpStatus};

/// Seconds each operation takes: initialising the sensors and services, a
/// manipulator reaching down and gripping (Workpartner's hands, section
/// 5.1), handing a ball, and the legs reconfiguring for a movement mode.
pub const INIT_SECONDS: f64 = 1.0;
pub const TAKE_SECONDS: f64 = 4.0;
pub const LEAVE_SECONDS: f64 = 3.0;
pub const BALL_SECONDS: f64 = 2.0;
pub const MOVEMODE_SECONDS: f64 = 2.0;

/// One started operation.
#[derive(Debug, Clone, PartialEq)]
pub struct Pending {
    pub id: OpId,
    pub op: AsyncOp,
    /// Simulated time at which it completes, s.
    pub due: f64,
    pub status: OpStatus,
}

pub fn duration(op: &AsyncOp) -> f64 {
    match op {
        AsyncOp::Init(_) => INIT_SECONDS,
        AsyncOp::Manipulate(ManipTask::Take) => TAKE_SECONDS,
        AsyncOp::Manipulate(ManipTask::Leave) => LEAVE_SECONDS,
        AsyncOp::Manipulate(ManipTask::GetBall | ManipTask::GiveBall) => BALL_SECONDS,
        AsyncOp::MoveMode(_) => MOVEMODE_SECONDS,
    }
}

/// The operations in start order; ids count from 1.
#[derive(Debug, Clone, Default)]
pub struct Ops {
    list: Vec<Pending>,
}

impl Ops {
    pub fn push(&mut self, op: AsyncOp, now: f64) -> OpId {
        let id = OpId(self.list.len() as u32 + 1);
        self.list.push(Pending {
            id,
            due: now + duration(&op),
            op,
            status: OpStatus::Pending,
        });
        id
    }

    pub fn get(&self, id: OpId) -> Option<&Pending> {
        (id.0 as usize)
            .checked_sub(1)
            .and_then(|i| self.list.get(i))
    }

    /// Operations due by `now` and still pending, oldest first.
    pub fn due(&self, now: f64) -> Vec<(OpId, AsyncOp)> {
        self.list
            .iter()
            .filter(|p| p.status == OpStatus::Pending && p.due <= now + 1e-9)
            .map(|p| (p.id, p.op.clone()))
            .collect()
    }

    pub fn finish(&mut self, id: OpId, status: OpStatus) {
        if let Some(p) = (id.0 as usize)
            .checked_sub(1)
            .and_then(|i| self.list.get_mut(i))
        {
            p.status = status;
        }
    }

    /// A manipulation is under way: a second one is refused.
    pub fn manipulating(&self) -> bool {
        self.list
            .iter()
            .any(|p| p.status == OpStatus::Pending && matches!(p.op, AsyncOp::Manipulate(_)))
    }
}
