//! The planners' tests that write their worlds and plans as scenario text.
//! They need the language, which sits above the planners, so they live in
//! this crate and reach the planners through their public items; the
//! planners' other unit tests build worlds with fixtures, beside the code
//! (issue 40: the planners become a crate below the language).

mod astar_rotating;
mod hybrid_astar;
mod potential;
mod sampling;
