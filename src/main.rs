fn main() {
    println!("ssitrace");
}
