// Anchor of a precompiled-header target: nothing to compile of its own.
