//! Files: the project's own log format and track exports.
