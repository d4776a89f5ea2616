// Replaced by the eval sources.
