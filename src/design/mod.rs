//! A design as tiers (scratch: the lead's draft of issue 23's core).
pub mod meets;
pub mod reangle;
