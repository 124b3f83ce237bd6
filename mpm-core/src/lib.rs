//! Explicit Material Point Method (thesis chapters 7-10, appendix E).
