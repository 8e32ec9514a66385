//! Mechanisms declared with the toolkit.
