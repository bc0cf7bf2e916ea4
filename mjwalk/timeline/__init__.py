"""The timeline stage: per-frame humanoid poses of walks and reaches in a scene, playback and
collision checks."""
