//! Force-triggered events: inside a time window, when the instrument's force reaches a threshold, an
//! action takes over until the window ends (a force-controlled segment).

use serde::{Deserialize, Serialize};

/// An event of one track.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ForceEvent {
    /// A name, for logs and for later triggers that refer to this event.
    #[serde(default)]
    pub name: String,
    /// The window opens, s from the skill's start.
    pub from_s: f64,
    /// The window closes, s; the action's effect ends here.
    pub until_s: f64,
    /// The event fires the first cycle inside the window in which the force on the instrument (its
    /// magnitude, from the strain gauges) reaches this, N ...
    pub threshold_n: f64,
    /// ... and has stayed at or above it for this long, s (0: at once). A pull that stops at a
    /// passing spike (a coil catching as the thread is drawn through it) has not reached its force.
    #[serde(default)]
    pub sustain_s: f64,
    /// It also fires, whatever this instrument's force, in the first cycle of its window after an
    /// event of this name fired: on another track (two pulls stop together at the first one's set
    /// force: the other pulling on tears the thread out of the jaws that stopped), or another event
    /// of this one (a pull that stopped at its force lets go when its window opens).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fires_with: Option<String>,
    /// What happens.
    pub action: ForceAction,
}

/// What a fired event does, from the cycle it fires until its window closes.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceAction {
    /// Open the jaw to this angle (release what it holds), rad.
    OpenJaw {
        /// The opening, rad.
        jaw_rad: f64,
    },
    /// Stop the tip where it was commanded when the event fired (stop pushing).
    Hold,
    /// Keep a thread's tension: while the gauge reads more than `set_force_n` the tip gives way
    /// along the force, at `rate_m_per_n_s` for each newton over it, and while it reads less, the tip
    /// comes back towards its track at the same rate per newton under it (an admittance about the
    /// track, one-sided: never further on than the track), as far as the arm reaches. For a thread
    /// kept taut without tearing it from another instrument's jaws, as in a wind round the jaws.
    Give {
        /// The force the tip gives above, N.
        set_force_n: f64,
        /// How fast it gives per newton over (or comes back per newton under) the set force, m/(N s).
        rate_m_per_n_s: f64,
    },
}
