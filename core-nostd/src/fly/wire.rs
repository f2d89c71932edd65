//! The fly model as the generic machinery sees it: its one phase (a step, like the bee's),
//! its request and reply, which are also its wire messages.

use crate::model::{Model, Phase};
use crate::{Checked, Result, Scalar, StepCtx};

use super::{FlyDecision, FlyFrame, FlyParams, FlyState};

/// Neighbours in a fly sensor frame on the wire (spec §1.6: 16 on devices).
pub const WIRE_FLY_NEIGHBOURS: usize = 16;
/// Obstacle surfaces in a fly sensor frame on the wire (spec §2.5: at most 4).
pub const WIRE_FLY_SURFACES: usize = 4;

/// The fly sensor frame with the wire capacities.
pub type WireFlyFrame<S> = FlyFrame<S, WIRE_FLY_NEIGHBOURS, WIRE_FLY_SURFACES>;

wire_type! {
    /// Request: run [`step()`](super::step()).
    #[derive(Clone, Debug, PartialEq)]
    pub struct FlyStepRequest<S> {
        /// The insect's state.
        pub state: FlyState<S>,
        /// What it senses.
        pub frame: WireFlyFrame<S>,
        /// Seed, agent id and step: the inputs of its random numbers (escape angle, white
        /// and Gaussian noise), and its own id.
        pub ctx: StepCtx,
    }

    /// Reply to [`FlyStepRequest`]: the decision and the insect's next state.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct FlyStepReply<S> {
        /// The preferred velocity and whether ORCA was infeasible.
        pub decision: FlyDecision<S>,
        /// The state for the next step.
        pub state: FlyState<S>,
    }
}

impl<S: Scalar> FlyStepRequest<S> {
    /// Checks `params`, then runs the [`FlyStep`] phase on the request.
    pub fn run(&self, params: &FlyParams<S>) -> Result<FlyStepReply<S>> {
        FlyStep::run(&(*params).checked()?, self)
    }
}

/// The fly's one phase (ren2016 Algorithm 1): every insect integrates its forces into a
/// preferred velocity, ORCA makes it collision-free, and the insect moves.
#[derive(Clone, Copy, Debug)]
pub struct FlyStep;

impl<S: Scalar> Phase<FlyParams<S>> for FlyStep {
    const NAME: &'static str = "step";
    type Request = FlyStepRequest<S>;
    type Reply = FlyStepReply<S>;
    fn run(params: &Checked<FlyParams<S>>, req: &FlyStepRequest<S>) -> Result<FlyStepReply<S>> {
        super::step_checked(&req.state, &req.frame, params, req.ctx)
            .map(|(state, decision)| FlyStepReply { decision, state })
    }
}

impl<S: Scalar> Model for FlyParams<S> {
    const NAME: &'static str = "fly";
    type State = FlyState<S>;
    type Phases = (FlyStep,);
}
