int sharedThing() { return 1; }
