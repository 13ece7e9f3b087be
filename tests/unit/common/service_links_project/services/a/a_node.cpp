int aNode() { return 3; }
