"""specpoly_light: an ESPHome external component (see README.md)."""
