//! Measurement readers and output writers (filled in by the io work).
