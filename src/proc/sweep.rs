//! laguerre, sorting, spline, outrectp, roottesting (being written).
