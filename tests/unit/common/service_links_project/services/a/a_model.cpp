int aModel() { return 2; }
