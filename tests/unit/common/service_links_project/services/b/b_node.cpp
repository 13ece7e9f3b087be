int bNode() { return 5; }
