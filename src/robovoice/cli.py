import sys
def main() -> int:
    print("robovoice")
    return 0
