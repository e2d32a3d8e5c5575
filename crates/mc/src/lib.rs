//! Monte Carlo integration (book 3, chapters 2 and 3).
