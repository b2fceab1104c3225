G21 (metric (mm))
