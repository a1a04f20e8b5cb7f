"""Shared cached results that several stages and studies read: the rail's moving kernel and surface tables, the friction curves."""
