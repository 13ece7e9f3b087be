int bModel() { return 4; }
